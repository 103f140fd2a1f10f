//! The crate's WGSL modules and the composer that resolves their imports.

/// The WGSL modules of this crate, importable as `#import render::<name>`.
pub const WGSL_MODULES: &[skyscape_wgsl::Module] = &[
    skyscape_wgsl::Module {
        name: "render::tonemap",
        source: include_str!("../shaders/tonemap.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::present",
        source: include_str!("../shaders/present.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::terrain_shading",
        source: include_str!("../shaders/terrain_shading.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::volume_shadow",
        source: include_str!("../shaders/volume_shadow.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::terrain",
        source: include_str!("../shaders/terrain.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::terrain_aerial_vertex",
        source: include_str!("../shaders/terrain_aerial_vertex.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::vertex_air",
        source: include_str!("../shaders/vertex_air.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::vertex_air_compute",
        source: include_str!("../shaders/vertex_air_compute.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::terrain_rung_aerial_vertex",
        source: include_str!("../shaders/terrain_rung_aerial_vertex.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::sky_rung",
        source: include_str!("../shaders/sky_rung.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::terrain_rung",
        source: include_str!("../shaders/terrain_rung.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::rung_air",
        source: include_str!("../shaders/rung_air.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::clouds",
        source: include_str!("../shaders/clouds.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::scene_distance",
        source: include_str!("../shaders/scene_distance.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::volume_distance",
        source: include_str!("../shaders/volume_distance.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::volume_composite",
        source: include_str!("../shaders/volume_composite.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::volume_air",
        source: include_str!("../shaders/volume_air.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::air_segment",
        source: include_str!("../shaders/air_segment.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::rung_sky",
        source: include_str!("../shaders/rung_sky.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::rung_closed_form",
        source: include_str!("../shaders/rung_closed_form.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::rung_single",
        source: include_str!("../shaders/rung_single.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::cloud_air_io",
        source: include_str!("../shaders/cloud_air_io.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::cloud_air_rung",
        source: include_str!("../shaders/cloud_air_rung.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::volume_clouds",
        source: include_str!("../shaders/volume_clouds.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::cloud_order",
        source: include_str!("../shaders/cloud_order.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::cloud_order_composite",
        source: include_str!("../shaders/cloud_order_composite.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::billboard_air",
        source: include_str!("../shaders/billboard_air.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::billboard_clouds_io",
        source: include_str!("../shaders/billboard_clouds_io.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::billboard_clouds",
        source: include_str!("../shaders/billboard_clouds.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::billboard_clouds_rung",
        source: include_str!("../shaders/billboard_clouds_rung.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::billboard_air_io",
        source: include_str!("../shaders/billboard_air_io.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::billboard_air_rung",
        source: include_str!("../shaders/billboard_air_rung.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "render::display",
        source: include_str!("../shaders/display.wgsl"),
    },
];

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
    /// The embedded list is the folder `build.rs` validates: no file left out, none extra.
    #[test]
    fn wgsl_modules_are_the_files_build_rs_validates() {
        let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
        let mut listed: Vec<_> = super::WGSL_MODULES.iter().map(|m| m.name).collect();
        listed.sort_unstable();
        assert_eq!(
            listed,
            skyscape_wgsl::build::module_names("render", &folder).unwrap()
        );
    }

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
                skyscape_wgsl::rust_layout!(PresentParameters {
                    sun_disc_radiance,
                    cos_sun_radius,
                    planet_radius,
                    exposure,
                    dither_seed,
                    padding,
                }),
                wgsl("render::present", "PresentParameters"),
            ),
        ];
        #[cfg(feature = "gpu")]
        let twins = {
            use crate::gpu::cloud_composite::VolumeDistanceParams;
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
                    padding0,
                    padding1,
                    padding2,
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
                }),
                wgsl("render::clouds", "CloudComposite"),
            ));
            twins
        };
        for (rust, wgsl) in twins {
            rust.check_twin_of(&wgsl).unwrap_or_else(|e| panic!("{e}"));
        }
    }
}
