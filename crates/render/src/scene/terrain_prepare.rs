//! The scene's terrain prepared: the heightfield from its source, its normals, horizon
//! maps and albedo (`Scene::terrain`), taken from the preparation cache when the
//! `[terrain]` section and its heightfield file did not change.

use terrain::generate::{Fractal, GeneratorParams};
use terrain::{Algorithm, Heightfield, HorizonOptions, NormalMap};

use super::assemble::metres;
use super::prepare::*;
use super::{HorizonVariant, MaterialsModel, PrepareCache, Scene, SceneError};
use crate::terrain_colour::read_colour_png;
use crate::terrain_shading::AlbedoRamp;

impl Scene {
    /// The terrain for this scene from `cache` (built and kept when its section or
    /// heightfield file changed), or `None` without `[terrain]`.
    pub(super) fn cached_terrain(
        &self,
        cache: &PrepareCache,
    ) -> Result<Option<PreparedTerrain>, SceneError> {
        let terrain = match &self.file.terrain {
            Some(section) => {
                let source = section
                    .png16
                    .as_ref()
                    .map(|p| &p.path)
                    .or(section.raw_f32.as_ref().map(|r| &r.path))
                    .map(|path| self.resolve(path));
                let stamp = |path: std::path::PathBuf| {
                    let meta = std::fs::metadata(&path).ok();
                    let (len, modified) = meta.map_or((0, None), |m| (m.len(), m.modified().ok()));
                    (path, len, modified)
                };
                let key = super::cache::TerrainKey {
                    section: section.clone(),
                    file: source.map(stamp),
                    colour_file: section
                        .colour
                        .as_ref()
                        .map(|c| stamp(self.resolve(&c.path))),
                    pole_north: self.pole_north() as i8,
                };
                Some(cache.terrain(key, || {
                    self.terrain()?.ok_or_else(|| unreachable_terrain(self))
                })?)
            }
            None => None,
        };
        Ok(terrain)
    }

    /// The heightfield, normals, horizon maps and albedo, or `None` without `[terrain]`.
    fn terrain(&self) -> Result<Option<PreparedTerrain>, SceneError> {
        let Some(section) = &self.file.terrain else {
            return Ok(None);
        };
        let given = [
            section.procedural.is_some(),
            section.png16.is_some(),
            section.raw_f32.is_some(),
        ];
        if given.iter().filter(|&&g| g).count() != 1 {
            return Err(self.invalid(
                &["terrain"],
                format!("{} sources", given.iter().filter(|&&g| g).count()),
                "give exactly one of [terrain.procedural], [terrain.png16], [terrain.raw_f32]"
                    .into(),
            ));
        }
        let heightfield = if let Some(p) = &section.procedural {
            let mut params = GeneratorParams::new(p.size, p.size, p.cell_size, p.seed);
            params.amplitude = p.relief;
            params.octaves = p.octaves;
            if let Some(w) = p.wavelength {
                params.wavelength = w;
            }
            if p.ridged {
                params.fractal = Fractal::Ridged;
            }
            terrain::generate::generate(&params).map_err(|e| {
                let (key, value) = match terrain_field(&e) {
                    "width" | "height" | "width * height" => ("size", p.size.to_string()),
                    "spacing" => ("cell_size", metres(p.cell_size)),
                    "amplitude" => ("relief", metres(p.relief)),
                    "wavelength" => ("wavelength", metres(params.wavelength)),
                    "octaves" => ("octaves", p.octaves.to_string()),
                    _ => ("seed", p.seed.to_string()),
                };
                self.terrain_error(&["terrain", "procedural", key], value, e)
            })?
        } else if let Some(p) = &section.png16 {
            let path = self.resolve(&p.path);
            Heightfield::open_png16(&path, p.cell_size, p.height_scale, p.height_offset).map_err(
                |e| {
                    let (key, value) = match terrain_field(&e) {
                        "spacing" => ("cell_size", metres(p.cell_size)),
                        "scale" | "scale_m_per_count" => {
                            ("height_scale", p.height_scale.to_string())
                        }
                        "offset" => ("height_offset", metres(p.height_offset)),
                        _ => ("path", format!("\"{}\"", path.display())),
                    };
                    self.terrain_error(&["terrain", "png16", key], value, e)
                },
            )?
        } else if let Some(p) = &section.raw_f32 {
            let path = self.resolve(&p.path);
            Heightfield::open_raw_f32_le(&path, p.width, p.height, p.cell_size)
                .and_then(|hf| hf.with_vertical_scale(p.height_scale))
                .map_err(|e| {
                    let (key, value) = match terrain_field(&e) {
                        "width" => ("width", p.width.to_string()),
                        "height" => ("height", p.height.to_string()),
                        "spacing" => ("cell_size", metres(p.cell_size)),
                        "vertical_scale" => ("height_scale", p.height_scale.to_string()),
                        _ => ("path", format!("\"{}\"", path.display())),
                    };
                    self.terrain_error(&["terrain", "raw_f32", key], value, e)
                })?
        } else {
            unreachable!("exactly one source was checked above")
        };
        if heightfield.width() < 2 || heightfield.height() < 2 {
            return Err(self.invalid(
                &["terrain"],
                format!("{}×{} texels", heightfield.width(), heightfield.height()),
                "a surface needs at least 2×2 texels".into(),
            ));
        }
        self.check_camera_above(&heightfield)?;
        // The renderer places the heightfield flat (no Earth curvature), so its
        // shadows are baked flat too.
        let options = HorizonOptions::flat();
        let horizon = match (section.horizon, section.horizon_azimuths) {
            (HorizonVariant::EastWest, None) => HorizonMaps::EastWest(
                terrain::bake_east_west(&heightfield, &options, Algorithm::HullSweep).map_err(
                    |e| self.terrain_error(&["terrain", "horizon"], "\"east-west\"".into(), e),
                )?,
            ),
            (HorizonVariant::EastWest, Some(n)) => {
                return Err(self.invalid(
                    &["terrain", "horizon_azimuths"],
                    n.to_string(),
                    "only used with horizon = \"azimuths\"".into(),
                ));
            }
            (HorizonVariant::Azimuths, None) => {
                return Err(self.invalid(
                    &["terrain", "horizon"],
                    "\"azimuths\"".into(),
                    "needs horizon_azimuths = N".into(),
                ));
            }
            (HorizonVariant::Azimuths, Some(n)) => HorizonMaps::Azimuths(
                terrain::bake_azimuths(&heightfield, n, &options, Algorithm::HullSweep).map_err(
                    |e| self.terrain_error(&["terrain", "horizon_azimuths"], n.to_string(), e),
                )?,
            ),
        };
        let albedo = AlbedoRamp::new(&section.albedo).map_err(|(key, value, reason)| {
            self.invalid(&["terrain", "albedo", key], value, reason)
        })?;
        let materials = match (section.materials, &section.procedural_materials) {
            (MaterialsModel::Ramp, None) => None,
            (MaterialsModel::Ramp, Some(_)) => {
                return Err(self.invalid(
                    &["terrain", "procedural_materials"],
                    "a section".into(),
                    "only used with materials = \"procedural\"".into(),
                ));
            }
            (MaterialsModel::Procedural, given) => Some(
                given
                    .clone()
                    .unwrap_or_default()
                    .params(self.pole_north())
                    .map_err(|(key, value, reason)| {
                        self.invalid(&["terrain", "procedural_materials", key], value, reason)
                    })?,
            ),
        };
        let colour = match &section.colour {
            Some(c) => {
                let extent = [
                    (heightfield.width() - 1) as f64 * heightfield.spacing(),
                    (heightfield.height() - 1) as f64 * heightfield.spacing(),
                ];
                let texture = read_colour_png(&self.resolve(&c.path), c.cell_size, extent)
                    .map_err(|(key, value, reason)| {
                        self.invalid(&["terrain", "colour", key], value, reason)
                    })?;
                Some(std::sync::Arc::new(texture))
            }
            None => None,
        };
        let normals = NormalMap::from_heightfield(&heightfield);
        Ok(Some(PreparedTerrain {
            heightfield,
            normals,
            horizon,
            albedo,
            materials,
            colour,
            aerial_perspective: section.aerial_perspective,
        }))
    }
}

impl Scene {
    /// +1 where the pole the terrain's shaded slopes face is north (the scene's
    /// `[time] latitude_deg` ≥ 0, or no `[time]`), −1 in the southern hemisphere.
    fn pole_north(&self) -> f32 {
        match &self.file.time {
            Some(time) if time.latitude_deg < 0.0 => -1.0,
            _ => 1.0,
        }
    }
}

/// The field a terrain error names, or "" when it names none.
fn terrain_field(error: &terrain::TerrainError) -> &'static str {
    use terrain::TerrainError as E;
    match error {
        E::InvalidParameter { field, .. }
        | E::ZeroSize { field, .. }
        | E::TooLarge { field, .. } => field,
        _ => "",
    }
}

/// `Scene::terrain` returned nothing for a scene with `[terrain]`: not reachable (it
/// builds a terrain for every section), an error rather than a panic.
fn unreachable_terrain(scene: &Scene) -> SceneError {
    scene.invalid(
        &["terrain"],
        "a section".into(),
        "no terrain was built for it".into(),
    )
}
