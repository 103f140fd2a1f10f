// Shared constants. Twin: skyscape_wgsl::common (Rust), same names in SCREAMING_CASE.
// f32 literals are the nearest f32 to the exact value.

const PI: f32 = 3.141592653589793;
const TAU: f32 = 6.283185307179586;
const INV_PI: f32 = 0.3183098861837907;
const INV_FOUR_PI: f32 = 0.07957747154594767;
