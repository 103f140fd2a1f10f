// Where a terrain point reads the volumetric cloud's shadow map
// (render::volume_clouds::CloudShadow): no bindings, so parity can call it.
#import cloudlight::shadow_map

// Twin of render::volume_clouds::volume_shadow_texel: `point` (east/north/up, metres)
// carried along unit `to_sun` to the plane at altitude `plane`, in texel-centre
// coordinates ((x − origin)/cell − ½: texel (i, j)'s centre is (i, j)); cloudlight's
// shadow_map_texel, which another cloud's march shares.
fn volume_shadow_texel(point: vec3<f32>, to_sun: vec3<f32>, plane: f32, origin: vec2<f32>, cell_size: f32) -> vec2<f32> {
    return shadow_map_texel(point, to_sun, plane, origin, cell_size);
}
