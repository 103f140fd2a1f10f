//! Slice-by-slice light attenuation (Dobashi et al. 2000). Twin of
//! `shaders/cloudlight/slice_attenuation.wgsl`.

/// Light leaving a slice: `light_from_previous_slice · (1 − (1 − attenuation_ratio) ·
/// smoothed_density)`; `smoothed_density` and `attenuation_ratio` in [0, 1].
pub fn slice_attenuation(
    light_from_previous_slice: f32,
    smoothed_density: f32,
    attenuation_ratio: f32,
) -> f32 {
    crate::propagate::attenuate(
        light_from_previous_slice,
        smoothed_density,
        attenuation_ratio,
    )
}

#[cfg(test)]
mod tests {
    use super::slice_attenuation;

    #[test]
    fn empty_slices_pass_all_light_and_dense_ones_the_ratio() {
        assert_eq!(slice_attenuation(0.7, 0.0, 0.3), 0.7);
        approx::assert_relative_eq!(slice_attenuation(1.0, 1.0, 0.3), 0.3);
    }

    #[test]
    fn attenuation_compounds_through_slices_like_beer() {
        // n dense slices of ratio r pass r^n: the discrete Beer–Lambert law.
        let light = (0..10).fold(1.0f32, |light, _| slice_attenuation(light, 1.0, 0.9));
        approx::assert_relative_eq!(light, 0.9f32.powi(10), max_relative = 1e-6);
    }
}
