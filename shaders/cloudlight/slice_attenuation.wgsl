// Slice-by-slice light attenuation (Dobashi et al. 2000): light leaving a volume slice is the
// light that reached it from the previous slice (towards the sun) times the slice's
// attenuation, 1 − (1 − attenuation_ratio)·density, with density in [0, 1] the
// smoothed cloud density and attenuation_ratio the fraction of light a fully dense
// slice lets through. Twin: cloudlight::slice (Rust).
fn slice_attenuation(light_from_previous_slice: f32, smoothed_density: f32, attenuation_ratio: f32) -> f32 {
    return light_from_previous_slice * (1.0 - (1.0 - attenuation_ratio) * smoothed_density);
}
