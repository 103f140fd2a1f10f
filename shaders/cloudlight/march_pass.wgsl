// The view ray-march of a CloudVolume: each pixel of a pinhole camera runs
// field_march's march_pixel (march_pass_pixel), its density field the volume's grid
// (cloudlight::gpu::MarchPass binds cloudlight::density_source to
// cloudlight::density_grid), from a fragment stage over march_raster's triangle
// (march_fragment) or, where fragment shaders cannot write storage buffers, a compute
// stage (march_main). Twin: cloudlight::march::render_image::<f32> on a CloudVolume
// (whose density lookup is f64 rounded once; this one is f32).
#import cloudlight::field_march
#import cloudlight::march_raster

@group(0) @binding(0) var<uniform> params: MarchParams;
// Two texels per pixel (x fastest): (radiance rgb, transmittance), (depth, 0, 0, 0).
@group(0) @binding(1) var<storage, read_write> image_out: array<vec4<f32>>;
// The distance (m) along each pixel's ray (x fastest) where its march stops; read only
// when view.y is 1 (otherwise a placeholder is bound).
@group(0) @binding(2) var<storage, read> max_distance: array<f32>;

// Marches `pixel` (x, y; row 0 at the top) into image_out; pixels outside the image
// write nothing.
fn march_pass_pixel(pixel: vec2<u32>) {
    let size = params.image.xy;
    if pixel.x >= size.x || pixel.y >= size.y {
        return;
    }
    // Temporally amortised (view.z = 1): only the pixels the reprojection left to march.
    if params.view.z == 1u && image_out[2u * (pixel.x + size.x * pixel.y) + 1u].y == 0.0 {
        return;
    }
    var limit = INFINITE_DISTANCE;
    if params.view.y != 0u {
        limit = max_distance[pixel.x + size.x * pixel.y];
    }
    let result = march_pixel(params, pixel, limit);
    let index = 2u * (pixel.x + size.x * pixel.y);
    image_out[index] = vec4<f32>(result.radiance, result.transmittance);
    image_out[index + 1u] = vec4<f32>(result.depth, 0.0, 0.0, 0.0);
}

// One fragment per pixel of march_raster's triangle.
@fragment
fn march_fragment(@builtin(position) position: vec4<f32>) {
    march_pass_pixel(march_raster_pixel(position));
}

// One invocation per pixel, 8×8 per workgroup.
@compute @workgroup_size(8, 8)
fn march_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    march_pass_pixel(gid.xy);
}
