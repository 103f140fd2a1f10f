//! The crate's WGSL modules and the composer that resolves their imports.

/// The WGSL modules of this crate, importable as `#import render::<name>`.
pub const WGSL_MODULES: &[skyscape_wgsl::Module] =
    include!(concat!(env!("OUT_DIR"), "/wgsl_modules.rs"));

/// A composer with the common, `atmos`, `terrain`, `celestial` and `render` modules.
pub fn composer() -> skyscape_wgsl::Composer {
    let mut composer = atmos::composer();
    add_composed_crates(&mut composer);
    composer
}

/// Adds the modules of the crates `render` composes (beyond atmos and common) to a
/// composer: terrain's, celestial's, cloudlight's and its own.
pub fn add_composed_crates(composer: &mut skyscape_wgsl::Composer) {
    composer
        .add_modules(terrain::WGSL_MODULES)
        .expect("terrain WGSL module names are unique and well formed");
    composer
        .add_modules(celestial::WGSL_MODULES)
        .expect("celestial WGSL module names are unique and well formed");
    composer
        .add_modules(cloudlight::WGSL_MODULES)
        .expect("cloudlight WGSL module names are unique and well formed");
    composer
        .add_modules(WGSL_MODULES)
        .expect("render WGSL module names are unique and well formed");
}

#[cfg(test)]
mod wgsl_tests {
    #[test]
    fn every_module_composes_and_validates() {
        let composer = super::composer();
        for module in super::WGSL_MODULES {
            let source = composer.compose_module(module.name).unwrap();
            skyscape_wgsl::validate(module.name, &source).unwrap();
        }
    }

    /// The `#[repr(C)]` uniform twins have the size and field offsets of their WGSL
    /// structs.
    #[test]
    fn uniform_twins_match_their_wgsl_layouts() {
        use crate::present::PresentParameters;
        use crate::terrain_materials::MaterialsUniform;
        use crate::terrain_shading::AlbedoRampUniform;
        let composer = super::composer();
        let wgsl = |module: &str, name: &str| {
            let source = composer.compose_module(module).unwrap();
            let parsed = skyscape_wgsl::validate(module, &source).unwrap();
            skyscape_wgsl::struct_layout(&parsed, name)
                .unwrap_or_else(|| panic!("no struct {name} in {module}"))
        };
        let twins = [
            (
                skyscape_wgsl::rust_layout!(AlbedoRampUniform {
                    heights,
                    colors,
                    steep_color,
                    stop_count,
                    cos_steep,
                    cos_gentle,
                    padding,
                }),
                wgsl("render::terrain_shading", "AlbedoRamp"),
            ),
            (
                skyscape_wgsl::rust_layout!(MaterialsUniform {
                    rock_albedo,
                    snow_line,
                    grass_albedo,
                    snow_line_aspect,
                    snow_albedo,
                    grass_line,
                    transition,
                    cos_rock_gentle,
                    cos_rock_steep,
                    cos_snow_gentle,
                    cos_snow_steep,
                    line_noise,
                    albedo_noise,
                    seed,
                    pole_north,
                    padding0,
                    padding1,
                    padding2,
                }),
                wgsl("render::terrain_materials", "MaterialParams"),
            ),
            (
                skyscape_wgsl::rust_layout!(PresentParameters {
                    sun_disc_radiance,
                    cos_sun_radius,
                    planet_radius,
                    exposure,
                    dither_seed,
                    display_transform,
                }),
                wgsl("render::present", "PresentParameters"),
            ),
        ];
        #[cfg(feature = "gpu")]
        let twins = {
            use crate::gpu::cloud_composite::VolumeDistanceParams;
            use crate::in_cloud_fog::InCloudFogUniforms;
            use crate::passes::cloud_layers::CloudComposite;
            use crate::passes::display::DisplayParameters;
            use crate::passes::terrain::uniforms::{TerrainUniform, VolumeShadowUniform};
            let mut twins = twins.to_vec();
            twins.push((
                skyscape_wgsl::rust_layout!(TerrainUniform {
                    view_projection,
                    camera,
                    spacing,
                    map_offset,
                    map_size,
                    sun_enu,
                    sun_angular_radius,
                    sky_irradiance,
                    sun_elevation,
                    sun_azimuth,
                    horizon_layers,
                    viewer_radius,
                    cloud_layer_count,
                    albedo,
                    radiance_scale,
                    pixel_angle,
                    procedural,
                    colour_enabled,
                    colour_size,
                    colour_texels_per_metre,
                    padding0,
                    materials,
                }),
                wgsl("render::terrain", "TerrainUniform"),
            ));
            twins.push((
                skyscape_wgsl::rust_layout!(VolumeDistanceParams {
                    camera,
                    near,
                    width,
                    height,
                    padding0,
                }),
                wgsl("render::volume_distance", "VolumeDistanceParams"),
            ));
            twins.push((
                skyscape_wgsl::rust_layout!(VolumeShadowUniform {
                    origin,
                    cell_size,
                    plane,
                    to_sun,
                    enabled,
                    resolution,
                    offset,
                    top,
                }),
                wgsl("render::terrain", "VolumeShadowUniform"),
            ));
            twins.push((
                skyscape_wgsl::rust_layout!(DisplayParameters {
                    width,
                    height,
                    exposure,
                    dither_seed,
                    display_transform,
                    padding_a,
                    padding_b,
                    padding_c,
                }),
                wgsl("render::display", "DisplayParameters"),
            ));
            twins.push((
                skyscape_wgsl::rust_layout!(CloudComposite {
                    camera,
                    viewer_radius,
                    near,
                    layer_count,
                    radiance_scale,
                    fog,
                }),
                wgsl("render::clouds", "CloudComposite"),
            ));
            twins.push((
                skyscape_wgsl::rust_layout!(InCloudFogUniforms {
                    radiance,
                    extinction,
                    optical_depth_up,
                    optical_depth_down,
                    band_above,
                    band_below,
                    enabled,
                    padding0,
                    padding1,
                    padding2,
                }),
                wgsl("render::in_cloud_fog", "InCloudFogUniforms"),
            ));
            twins
        };
        for (rust, wgsl) in twins {
            rust.check_twin_of(&wgsl).unwrap_or_else(|e| panic!("{e}"));
        }
    }
}
