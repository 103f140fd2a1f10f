//! Rust twins of `shaders/common/*.wgsl`. Same names, same arguments, bit-identical.

/// π, as `PI` in `common::constants`.
pub const PI: f32 = std::f32::consts::PI;
/// 2π, as `TAU` in `common::constants`.
pub const TAU: f32 = std::f32::consts::TAU;
/// 1/π, as `INV_PI` in `common::constants`.
pub const INV_PI: f32 = std::f32::consts::FRAC_1_PI;
/// 1/(4π), as `INV_FOUR_PI` in `common::constants`.
pub const INV_FOUR_PI: f32 = 0.079_577_47;

/// A world direction or offset (x east, y up, z south: a game engine's axes, render's
/// and `atmos::frame::LocalFrame`'s) in east-north-up axes (x east, y north, z up:
/// terrain, the clouds, celestial's horizontal coordinates, and atmos' planet frame at
/// the local origin): `(x, −z, y)`, a rotation (`common::frames::world_to_enu`).
pub fn world_to_enu<F: Copy + std::ops::Neg<Output = F>>(v: [F; 3]) -> [F; 3] {
    [v[0], -v[2], v[1]]
}

/// An east-north-up direction or offset in world axes: `(x, z, −y)`, the inverse of
/// [`world_to_enu`] (`common::frames::enu_to_world`).
pub fn enu_to_world<F: Copy + std::ops::Neg<Output = F>>(v: [F; 3]) -> [F; 3] {
    [v[0], v[2], -v[1]]
}

/// Chris Wellons' "lowbias32" integer hash (`common::hash::hash_u32`).
pub fn hash_u32(value: u32) -> u32 {
    let mut x = value;
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^= x >> 16;
    x
}

/// Order-dependent combination of a running hash with one more word
/// (`common::hash::hash_combine`).
pub fn hash_combine(seed: u32, value: u32) -> u32 {
    hash_u32(
        seed ^ (value
            .wrapping_add(0x9e37_79b9)
            .wrapping_add(seed << 6)
            .wrapping_add(seed >> 2)),
    )
}

/// The top 24 bits of a hash as a float in [0, 1) (`common::hash::unit_float_from_bits`).
pub fn unit_float_from_bits(bits: u32) -> f32 {
    (bits >> 8) as f32 * (1.0 / 16_777_216.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_frames_are_one_right_handed_rotation_apart() {
        // Up is up, north is −z in the world, east is east.
        assert_eq!(world_to_enu([0.0, 1.0, 0.0]), [0.0, 0.0, 1.0]);
        assert_eq!(world_to_enu([0.0, 0.0, -1.0]), [0.0, 1.0, 0.0]);
        assert_eq!(world_to_enu([1.0, 0.0, 0.0]), [1.0, 0.0, 0.0]);
        for v in [[1.5f32, -2.0, 3.25], [-0.0, 7.0, -1e-30]] {
            assert_eq!(enu_to_world(world_to_enu(v)), v);
            assert_eq!(world_to_enu(enu_to_world(v)), v);
        }
        // Right-handed both ways: east × north = up.
        let cross = |a: [f64; 3], b: [f64; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let (east, north) = ([1.0, 0.0, 0.0], [0.0, 0.0, -1.0]);
        assert_eq!(
            world_to_enu(cross(east, north)),
            cross(world_to_enu(east), world_to_enu(north))
        );
    }

    #[test]
    fn hash_is_a_bijection_sample_and_well_mixed() {
        // Known values pin the function (a change here must also change the WGSL).
        assert_eq!(hash_u32(0), 0);
        // Reference values computed independently (Python, 32-bit wrapping arithmetic).
        assert_eq!(hash_u32(1), 0x6889_90c0);
        assert_eq!(hash_u32(12345), 0x912e_fcf7);
        // Avalanche: flipping one input bit flips about half the output bits.
        let mut flipped = 0u64;
        let n = 4096u32;
        for i in 0..n {
            for bit in 0..32 {
                flipped += u64::from((hash_u32(i) ^ hash_u32(i ^ (1 << bit))).count_ones());
            }
        }
        let mean = flipped as f64 / f64::from(n * 32);
        assert!((mean - 16.0).abs() < 0.5, "mean flipped bits {mean}");
    }

    #[test]
    fn unit_float_range() {
        assert_eq!(unit_float_from_bits(0), 0.0);
        assert!(unit_float_from_bits(u32::MAX) < 1.0);
        assert_eq!(unit_float_from_bits(1 << 31), 0.5);
    }

    #[test]
    fn combine_is_order_dependent() {
        assert_ne!(
            hash_combine(hash_combine(7, 1), 2),
            hash_combine(hash_combine(7, 2), 1)
        );
    }
}
