// Where a terrain point reads the volumetric cloud's shadow map
// (render::volume_clouds::CloudShadow): no bindings, so parity can call it.

// Twin of render::volume_clouds::volume_shadow_texel: `point` (east/north/up, metres)
// carried along unit `to_sun` to the plane at altitude `plane`, in texel-centre
// coordinates ((x − origin)/cell − ½: texel (i, j)'s centre is (i, j)).
fn volume_shadow_texel(point: vec3<f32>, to_sun: vec3<f32>, plane: f32, origin: vec2<f32>, cell_size: f32) -> vec2<f32> {
    let t = (plane - point.z) / to_sun.z;
    let x = point.x + t * to_sun.x;
    let y = point.y + t * to_sun.y;
    return vec2<f32>((x - origin.x) / cell_size - 0.5, (y - origin.y) / cell_size - 0.5);
}
