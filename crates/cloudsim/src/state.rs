//! The two state layouts: one `bool` per cell ([`NaiveState`]) and 32 cells per `u32`
//! word along x ([`PackedState`], shared by the fast CPU path and the GPU).

use crate::model::checked_threshold;
use crate::rng::stream_key;
use crate::{Error, GridSize};
use skyscape_wgsl::common::hash_combine;

/// One `bool` per cell and field, linear index `x + nx * (y + ny * z)`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NaiveState {
    size: GridSize,
    /// Humidity.
    pub hum: Vec<bool>,
    /// Activation (phase transition).
    pub act: Vec<bool>,
    /// Cloud.
    pub cld: Vec<bool>,
}

impl NaiveState {
    /// All-false state.
    pub fn empty(size: GridSize) -> Result<Self, Error> {
        size.validate()?;
        let n = size.cells();
        Ok(Self {
            size,
            hum: vec![false; n],
            act: vec![false; n],
            cld: vec![false; n],
        })
    }

    /// Grid dimensions.
    pub fn size(&self) -> GridSize {
        self.size
    }

    /// Checks that the three vectors have `size.cells()` entries.
    pub fn check(&self) -> Result<(), Error> {
        let expected = self.size.cells();
        for (what, got) in [
            ("hum", self.hum.len()),
            ("act", self.act.len()),
            ("cld", self.cld.len()),
        ] {
            if got != expected {
                return Err(Error::SizeMismatch {
                    what,
                    got,
                    expected,
                });
            }
        }
        Ok(())
    }
}

/// 32 cells per `u32` along x: bit `i` of word `wx` of row `(y, z)` is cell
/// `x = 32 wx + i`; word index `wx + words_per_row * (y + ny * z)`. Bits past `nx` in
/// a row's last word are always zero.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PackedState {
    size: GridSize,
    /// Humidity words.
    pub hum: Vec<u32>,
    /// Activation words.
    pub act: Vec<u32>,
    /// Cloud words.
    pub cld: Vec<u32>,
}

impl PackedState {
    /// All-zero state.
    pub fn empty(size: GridSize) -> Result<Self, Error> {
        size.validate()?;
        let n = size.words();
        Ok(Self {
            size,
            hum: vec![0; n],
            act: vec![0; n],
            cld: vec![0; n],
        })
    }

    /// A reproducible random state: each cell's `hum`, `act`, `cld` is set with the
    /// given probabilities (quantised to 2^-16), drawn with the crate's hash from `seed`
    /// (streams 100..103, so they never coincide with the automaton's draws).
    /// A probability outside `[0, 1]` is [`Error::Probability`]; a positive one below
    /// 2^-16 is [`Error::ProbabilityResolution`] (it would act as 0).
    pub fn random(size: GridSize, seed: u32, hum: f32, act: f32, cld: f32) -> Result<Self, Error> {
        // The same checks as the model's probabilities: outside [0, 1] and positive
        // values below the draws' resolution (which would silently act as 0) are errors.
        let thresholds = [
            checked_threshold("hum", hum)?,
            checked_threshold("act", act)?,
            checked_threshold("cld", cld)?,
        ];
        let mut naive = NaiveState::empty(size)?;
        let fields = [
            (&mut naive.hum, thresholds[0], 100),
            (&mut naive.act, thresholds[1], 101),
            (&mut naive.cld, thresholds[2], 102),
        ];
        for (cells, t, stream) in fields {
            let key = stream_key(seed, 0, stream);
            for (i, cell) in cells.iter_mut().enumerate() {
                *cell = (hash_combine(key, i as u32) >> 16) < t;
            }
        }
        Self::from_naive(&naive)
    }

    /// Grid dimensions.
    pub fn size(&self) -> GridSize {
        self.size
    }

    /// Checks vector lengths and that padding bits are zero.
    pub fn check(&self) -> Result<(), Error> {
        let expected = self.size.words();
        for (what, words) in [("hum", &self.hum), ("act", &self.act), ("cld", &self.cld)] {
            if words.len() != expected {
                return Err(Error::SizeMismatch {
                    what,
                    got: words.len(),
                    expected,
                });
            }
            let wpr = self.size.words_per_row();
            let padding = !self.size.last_word_mask();
            if padding == 0 {
                continue; // rows of whole words have no padding bits
            }
            if let Some(row) = words
                .chunks_exact(wpr)
                .position(|row| row[wpr - 1] & padding != 0)
            {
                return Err(Error::PaddingBits {
                    what,
                    word: row * wpr + wpr - 1,
                });
            }
        }
        Ok(())
    }

    /// Packs a naive state.
    pub fn from_naive(naive: &NaiveState) -> Result<Self, Error> {
        naive.check()?;
        let size = naive.size;
        let nx = size.nx as usize;
        let wpr = size.words_per_row();
        let pack = |cells: &[bool]| {
            let mut words = vec![0u32; size.words()];
            for (row, bits) in cells.chunks_exact(nx).enumerate() {
                for (x, &b) in bits.iter().enumerate() {
                    words[row * wpr + x / 32] |= u32::from(b) << (x % 32);
                }
            }
            words
        };
        Ok(Self {
            size,
            hum: pack(&naive.hum),
            act: pack(&naive.act),
            cld: pack(&naive.cld),
        })
    }

    /// Unpacks into one bool per cell.
    pub fn to_naive(&self) -> NaiveState {
        let size = self.size;
        let nx = size.nx as usize;
        let wpr = size.words_per_row();
        let unpack = |words: &[u32]| {
            let mut cells = Vec::with_capacity(size.cells());
            for row in 0..size.rows() {
                for x in 0..nx {
                    cells.push(words[row * wpr + x / 32] >> (x % 32) & 1 == 1);
                }
            }
            cells
        };
        NaiveState {
            size,
            hum: unpack(&self.hum),
            act: unpack(&self.act),
            cld: unpack(&self.cld),
        }
    }

    /// `cld` of cell `(x, y, z)`; [`Error::CellOutOfRange`] outside the grid (an
    /// unchecked `x` would read a padding bit or the next row).
    pub fn cloud(&self, x: u32, y: u32, z: u32) -> Result<bool, Error> {
        self.size.check_cell(x, y, z)?;
        Ok(self.bit(&self.cld, x, y, z))
    }

    fn bit(&self, words: &[u32], x: u32, y: u32, z: u32) -> bool {
        let wpr = self.size.words_per_row();
        let row = y as usize + self.size.ny as usize * z as usize;
        words[row * wpr + x as usize / 32] >> (x % 32) & 1 == 1
    }

    /// Number of cells with `cld` set.
    pub fn cloud_count(&self) -> u64 {
        self.cld.iter().map(|w| u64::from(w.count_ones())).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pack_round_trip_and_padding() {
        let size = GridSize::new(37, 3, 2);
        let s = PackedState::random(size, 5, 0.5, 0.3, 0.7).unwrap();
        assert_eq!(s.hum.len(), 2 * 3 * 2);
        let mask = size.last_word_mask();
        for words in [&s.hum, &s.act, &s.cld] {
            for (i, w) in words.iter().enumerate() {
                if i % 2 == 1 {
                    assert_eq!(w & !mask, 0);
                }
            }
        }
        let n = s.to_naive();
        assert_eq!(PackedState::from_naive(&n).unwrap(), s);
        let ones = n.hum.iter().filter(|&&b| b).count();
        assert!(ones > 60 && ones < 160, "{ones}");
        assert_eq!(
            s.cloud(3, 1, 1).unwrap(),
            n.cld[size.index(3, 1, 1).unwrap()]
        );
    }

    #[test]
    fn bad_input() {
        assert!(PackedState::random(GridSize::new(4, 4, 4), 0, 1.5, 0.0, 0.0).is_err());
        assert!(PackedState::empty(GridSize::new(4, 0, 4)).is_err());
        let mut n = NaiveState::empty(GridSize::new(4, 4, 4)).unwrap();
        let mut p = PackedState::empty(GridSize::new(4, 2, 1)).unwrap();
        assert!(p.check().is_ok());
        p.cld[1] = 1 << 4;
        assert_eq!(
            p.check().unwrap_err(),
            Error::PaddingBits {
                what: "cld",
                word: 1
            }
        );
        n.act.pop();
        assert_eq!(
            PackedState::from_naive(&n).unwrap_err(),
            Error::SizeMismatch {
                what: "act",
                got: 63,
                expected: 64
            }
        );
    }
}
