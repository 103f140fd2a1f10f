// What a march pass draws when its per-pixel work runs as a fragment stage
// (cloudlight::gpu::FieldMarchPass on MarchStage::Fragment): one full-screen triangle
// over an image-sized attachment, so that one fragment runs at each pixel's centre, and
// that fragment's pixel.

// Vertex `index` (0..2) of a triangle covering clip space's [-1, 1]² square.
@vertex
fn march_raster_vertex(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

// The pixel (x, y; row 0 at the top) of a fragment at framebuffer `position`, whose
// pixel centres lie at .5: floor(position.xy).
fn march_raster_pixel(position: vec4<f32>) -> vec2<u32> {
    return vec2<u32>(floor(position.xy));
}
