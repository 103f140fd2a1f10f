//! Proper motions and parallaxes of the catalogue's stars, from the Hipparcos new
//! reduction (van Leeuwen 2007, *Hipparcos, the New Reduction of the Raw Data*,
//! CDS catalogue I/311; ESA, public), embedded as `data/hipparcos2_motion.bin`
//! (written by `data/hipparcos2_motion.py`; provenance in `data/README.md`).
//!
//! Format: the magic bytes `HIP2PM01`, then base-128 varints (signed values
//! zigzag-encoded): the row count, and per row in increasing Hipparcos number the
//! number's increase over the previous row's, μα·cos δ and μδ (0.01 mas/yr) and the
//! parallax (0.01 mas), exactly as the catalogue prints them.

use crate::angle::Angle;
use crate::error::{CelestialError, Result};

const DATA: &[u8] = include_bytes!("../../data/hipparcos2_motion.bin");
const MAGIC: &[u8] = b"HIP2PM01";

/// One star's motion and parallax.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct StarMotion {
    /// Hipparcos number.
    pub hip: usize,
    /// μα·cos δ per Julian year.
    pub proper_motion_ra_cos_dec: Angle,
    /// μδ per Julian year.
    pub proper_motion_dec: Angle,
    /// Annual parallax (may be ≤ 0: a measurement, not a distance).
    pub parallax: Angle,
}

struct Reader<'a> {
    bytes: &'a [u8],
    offset: usize,
}

impl Reader<'_> {
    fn corrupt(&self) -> CelestialError {
        CelestialError::CorruptData {
            field: "hipparcos2_motion.bin",
            offset: self.offset,
        }
    }

    fn unsigned(&mut self) -> Result<u64> {
        let mut value = 0_u64;
        for shift in (0..64).step_by(7) {
            let byte = *self.bytes.get(self.offset).ok_or_else(|| self.corrupt())?;
            self.offset += 1;
            value |= u64::from(byte & 0x7F) << shift;
            if byte & 0x80 == 0 {
                return Ok(value);
            }
        }
        Err(self.corrupt())
    }

    fn signed(&mut self) -> Result<i64> {
        let zigzag = self.unsigned()?;
        Ok((zigzag >> 1) as i64 ^ -((zigzag & 1) as i64))
    }
}

/// Every row of the embedded table, in increasing Hipparcos number.
pub(crate) fn hipparcos2_motions() -> Result<Vec<StarMotion>> {
    let mut reader = Reader {
        bytes: DATA,
        offset: MAGIC.len(),
    };
    if !DATA.starts_with(MAGIC) {
        return Err(CelestialError::CorruptData {
            field: "hipparcos2_motion.bin",
            offset: 0,
        });
    }
    let count = reader.unsigned()? as usize;
    let hundredth_mas = |value: i64| Angle::from_arcseconds(value as f64 * 1e-5);
    let mut hip = 0_usize;
    let mut rows = Vec::with_capacity(count);
    for _ in 0..count {
        let step = reader.unsigned()? as usize;
        if step == 0 {
            return Err(reader.corrupt());
        }
        hip += step;
        rows.push(StarMotion {
            hip,
            proper_motion_ra_cos_dec: hundredth_mas(reader.signed()?),
            proper_motion_dec: hundredth_mas(reader.signed()?),
            parallax: hundredth_mas(reader.signed()?),
        });
    }
    if reader.offset != DATA.len() {
        return Err(reader.corrupt());
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows as hip2.dat prints them (van Leeuwen 2007): Sirius (HIP 32349)
    /// −546.01, −1223.07 mas/yr, ϖ 379.21 mas; α Centauri A (71683) −3679.25,
    /// 473.67, 754.81; Groombridge 1830 (57939) 4003.98, −5813.62, 109.99.
    #[test]
    fn decodes_known_rows() {
        let rows = hipparcos2_motions().unwrap();
        let mas = |a: Angle| a.degrees() * 3.6e6;
        let find = |hip: usize| *rows.iter().find(|r| r.hip == hip).unwrap();
        for (hip, pm_ra, pm_dec, parallax) in [
            (32_349, -546.01, -1223.07, 379.21),
            (71_683, -3679.25, 473.67, 754.81),
            (57_939, 4003.98, -5813.62, 109.99),
        ] {
            let row = find(hip);
            assert!(
                (mas(row.proper_motion_ra_cos_dec) - pm_ra).abs() < 1e-6,
                "{row:?}"
            );
            assert!(
                (mas(row.proper_motion_dec) - pm_dec).abs() < 1e-6,
                "{row:?}"
            );
            assert!((mas(row.parallax) - parallax).abs() < 1e-6, "{row:?}");
        }
        assert!(rows.windows(2).all(|w| w[0].hip < w[1].hip));
    }
}
