// The density field a march reads: the GPU's DensityField (cloudlight::density), the
// interface cloudlight::field_march is written against. A pass composes its entry with
// this import bound to one source module (Composer::compose_module_bound; the Rust side
// is cloudlight::gpu::GpuDensitySource): cloudlight::density_grid (a CloudVolume) or
// cloudlight::density_shell (a procedural CloudShell). Each source defines, in the
// field's frame of metres:
//   field_density(p) -> f32                 dimensionless density at p (≥ 0)
//                                            (DensityField::density)
//   field_extinction_per_density() -> f32   σ_t per unit density, 1/m
//                                            (DensityField::extinction_per_density)
//   field_ray_spans(origin, direction)      the spans of the ray (unit direction, t ≥ 0)
//     -> RaySpans                            outside which the density is zero
//                                            (DensityField::ray_spans)
// and binds its parameters at group 0, binding 4 (a uniform) and binding 5 (a read-only
// storage buffer). This module is the trivial source, the empty field, that the march
// composes and validates with on its own.
#import cloudlight::ray_spans

fn field_density(p: vec3<f32>) -> f32 {
    return 0.0;
}

fn field_extinction_per_density() -> f32 {
    return 0.0;
}

fn field_ray_spans(origin: vec3<f32>, direction: vec3<f32>) -> RaySpans {
    return ray_spans_none();
}
