//! Property tests: every public constructor and validator of `atmos` takes arbitrary
//! input (NaN, ±inf, 0, huge, negative) without panicking, and every rejection is
//! the variant of the input at fault with a message naming the field.
//!
//! Only cheap constructors run (validation happens before any bake); 128 cases each.

use atmos::closed_form_sky::ClosedFormSky;
use atmos::dome::DomeResolution;
use atmos::frame::FrameCamera;
use atmos::lut::LutSettings;
use atmos::reference::ReferenceSettings;
use atmos::single_scattering::{SingleScatteringSettings, SingleScatteringSky};
use atmos::{AtmosError, Atmosphere, SkyQuery};
use glam::DVec3;
use proptest::prelude::*;

fn wild_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(0.0),
        Just(-0.0),
        Just(-1.0),
        Just(f64::MAX),
        Just(f64::MIN_POSITIVE),
        Just(1e300),
        -10.0..10.0f64,
        any::<f64>(),
    ]
}

fn wild_u32() -> impl Strategy<Value = u32> {
    prop_oneof![Just(0u32), Just(1), Just(u32::MAX), 0u32..70, any::<u32>()]
}

fn wild_vector() -> impl Strategy<Value = DVec3> {
    prop_oneof![
        (wild_f64(), wild_f64(), wild_f64()).prop_map(|(x, y, z)| DVec3::new(x, y, z)),
        (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z)),
    ]
}

/// Sets field `index` of an Earth atmosphere to `value`; returns the field's name.
fn perturb(atmosphere: &mut Atmosphere, index: usize, value: f64, channel: usize) -> &'static str {
    match index {
        0 => {
            atmosphere.planet_radius = value;
            "planet_radius"
        }
        1 => {
            atmosphere.top_radius = value;
            "top_radius"
        }
        2 => {
            atmosphere.rayleigh_scattering[channel] = value;
            "rayleigh_scattering"
        }
        3 => {
            atmosphere.rayleigh_scale_height = value;
            "rayleigh_scale_height"
        }
        4 => {
            atmosphere.mie_scattering[channel] = value;
            "mie_scattering"
        }
        5 => {
            atmosphere.mie_extinction[channel] = value;
            "mie_extinction"
        }
        6 => {
            atmosphere.mie_scale_height = value;
            "mie_scale_height"
        }
        7 => {
            atmosphere.mie_g = value;
            "mie_g"
        }
        8 => {
            atmosphere.ozone_absorption[channel] = value;
            "ozone_absorption"
        }
        9 => {
            atmosphere.ozone_center_altitude = value;
            "ozone_center_altitude"
        }
        10 => {
            atmosphere.ozone_half_width = value;
            "ozone_half_width"
        }
        11 => {
            atmosphere.ground_albedo[channel] = value;
            "ground_albedo"
        }
        12 => {
            atmosphere.sun_irradiance[channel] = value;
            "sun_irradiance"
        }
        _ => {
            atmosphere.sun_angular_radius = value;
            "sun_angular_radius"
        }
    }
}

fn is_named(error: &AtmosError, field: &str) -> Result<(), TestCaseError> {
    let message = error.to_string();
    prop_assert!(
        message.contains(field),
        "{message:?} does not name `{field}`"
    );
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn atmosphere_rejections_name_the_field(
        index in 0usize..14,
        channel in 0usize..3,
        value in wild_f64(),
    ) {
        let mut atmosphere = Atmosphere::earth();
        let field = perturb(&mut atmosphere, index, value, channel);
        let results = [
            atmosphere.validate(),
            atmosphere.to_uniforms().map(|_| ()),
            ClosedFormSky::new(&atmosphere).map(|_| ()),
            SingleScatteringSky::new(&atmosphere, SingleScatteringSettings::default()).map(|_| ()),
        ];
        for result in results {
            if let Err(error) = result {
                // Another field may be the one at fault when the change breaks a
                // relation (top above ground, extinction ≥ scattering, ...): the
                // message still names an atmosphere field.
                prop_assert!(
                    matches!(error, AtmosError::InvalidParameter { .. }),
                    "{error}"
                );
                let message = error.to_string();
                prop_assert!(message.starts_with("invalid atmosphere: `"), "{message}");
                if !matches!(index, 0 | 1 | 4 | 5 | 9 | 10) {
                    is_named(&error, field)?;
                }
            }
        }
    }

    #[test]
    fn camera_rejections_are_camera_errors(
        position in wild_vector(),
        forward in wild_vector(),
        up in wild_vector(),
        sun in wild_vector(),
        fov_y in wild_f64(),
        width in wild_u32(),
        height in wild_u32(),
        max_distance in prop::option::of(wild_f64()),
    ) {
        let position = DVec3::new(0.0, 0.0, 6_361_000.0) + position;
        if let Err(error) = FrameCamera::look_at(
            position, forward, up, fov_y, width, height, sun, max_distance,
        ) {
            prop_assert!(matches!(error, AtmosError::InvalidCamera { .. }), "{error}");
            prop_assert!(error.to_string().starts_with("invalid camera: `"), "{error}");
        }
        let query = SkyQuery::with_max_distance(
            6_360_000.0,
            position,
            forward,
            sun,
            max_distance.unwrap_or(f64::INFINITY),
        );
        if let Err(error) = query {
            prop_assert!(matches!(error, AtmosError::InvalidCamera { .. }), "{error}");
        }
    }

    #[test]
    fn settings_rejections_name_the_field(
        index in 0usize..16,
        value in wild_u32(),
        range in wild_f64(),
    ) {
        let mut lut = LutSettings::small();
        let field = match index {
            0 => { lut.transmittance_size[0] = value; "transmittance_size" }
            1 => { lut.transmittance_size[1] = value; "transmittance_size" }
            2 => { lut.transmittance_samples = value; "transmittance_samples" }
            3 => { lut.multiple_scattering_size[0] = value; "multiple_scattering_size" }
            4 => { lut.multiple_scattering_samples = value; "multiple_scattering_samples" }
            5 => { lut.multiple_scattering_direction_sqrt = value; "multiple_scattering_direction_sqrt" }
            6 => { lut.multiple_scattering_orders = value; "multiple_scattering_orders" }
            7 => { lut.sky_view_size[1] = value; "sky_view_size" }
            8 => { lut.sky_view_samples = value; "sky_view_samples" }
            9 => { lut.aerial_perspective_size[2] = value; "aerial_perspective_size" }
            10 => { lut.aerial_perspective_steps_per_slice = value; "aerial_perspective_steps_per_slice" }
            11 => { lut.pixel_samples = value; "pixel_samples" }
            _ => { lut.aerial_perspective_range = range as f32; "aerial_perspective_range" }
        };
        for result in [lut.validate(), lut.to_uniforms().map(|_| ())] {
            if let Err(error) = result {
                prop_assert!(matches!(error, AtmosError::InvalidLutSettings { .. }), "{error}");
                is_named(&error, field)?;
            }
        }
        let dome = DomeResolution { rings: value, segments: value / 2 };
        if let Err(error) = dome.validate() {
            prop_assert!(matches!(error, AtmosError::InvalidSetting { .. }), "{error}");
            prop_assert!(error.to_string().contains("rings") || error.to_string().contains("segments"));
        }
        let single = SingleScatteringSettings { view_samples: value, light_samples: 8 };
        if let Err(error) = single.validate() {
            is_named(&error, "view_samples")?;
        }
        let reference = ReferenceSettings { radius_size: value as usize, ..ReferenceSettings::low() };
        if let Err(error) = reference.validate() {
            is_named(&error, "radius_size")?;
        }
    }
}

#[test]
fn camera_and_lut_errors_say_which_input_they_belong_to() {
    let error = FrameCamera::look_at(
        DVec3::new(0.0, 0.0, 6_361_000.0),
        DVec3::X,
        DVec3::Z,
        f64::NAN,
        8,
        8,
        DVec3::Z,
        None,
    )
    .unwrap_err();
    assert!(
        error.to_string().starts_with("invalid camera: `fov_y`"),
        "{error}"
    );
    let settings = LutSettings {
        pixel_samples: 0,
        ..LutSettings::small()
    }
    .validate()
    .unwrap_err();
    assert!(
        settings
            .to_string()
            .starts_with("invalid LUT settings: `pixel_samples`"),
        "{settings}"
    );
}
