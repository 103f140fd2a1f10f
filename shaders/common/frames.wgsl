// The two frames of skyscape and the one rotation between them. Twin:
// skyscape_wgsl::common::{world_to_enu, enu_to_world} (Rust), bit-identical.
//
// * world: a game engine's (and render's and atmos::frame::LocalFrame's) axes: x east,
//   y up, z south (−z north), metres;
// * east-north-up (ENU): x east, y north, z up: terrain's heightfields, normals and sun
//   directions, the clouds, celestial's horizontal coordinates, and atmos' planet frame
//   at the local origin (the same axes, moved by the planet's radius along z).

// A world direction or offset in ENU axes: (x, −z, y).
fn world_to_enu(v: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(v.x, -v.z, v.y);
}

// An ENU direction or offset in world axes: (x, z, −y). Inverse of world_to_enu.
fn enu_to_world(v: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(v.x, v.z, -v.y);
}
