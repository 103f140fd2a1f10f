// The terrain's aerial perspective per vertex for a rung without tables (`[terrain]
// aerial_perspective = "per-vertex"` with `closed-form`, `closed-form-vertex` or
// `single`): what the compute pass over the drawn tiles' vertices
// (render::vertex_air_compute) and the terrain draw that reads its results
// (render::terrain_rung_aerial_vertex) share. Layout identical to
// render::gpu::vertex_air::VertexAirUniform.
struct VertexAirUniform {
    // The camera, planet-centred (m).
    camera_position: vec3<f32>,
    // Vertices of one tile's mesh (render::terrain_mesh::tile_mesh: grid and skirts).
    grid_vertices: u32,
    // Unit direction toward the light whose segments these are (the sun, or the moon).
    light: vec3<f32>,
    // Tiles drawn this frame.
    tile_count: u32,
}

// Where the segment of vertex `vertex` of tile `tile` starts in the segments array: two
// vec4 per vertex, transmittance then in-scatter (xyz).
fn vertex_air_index(air: VertexAirUniform, vertex: u32, tile: u32) -> u32 {
    return 2u * (tile * air.grid_vertices + vertex);
}
