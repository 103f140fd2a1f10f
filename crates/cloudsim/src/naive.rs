//! The reference implementation: one `bool` per cell, written for clarity, not speed.
//! The fast ([`crate::packed`]) and GPU implementations must match it bit for bit.

use crate::rng::{
    STREAM_ACTIVATION, STREAM_EXTINCTION, STREAM_HUMIDITY, lane_threshold, stream_key, uniform16,
};
use crate::{Boundary, Error, GridSize, Model, NaiveState};

/// Offsets `(dx, dy, dz)` whose `act` feeds a cell's `f_act`: x±1, x±2, y±1, y±2,
/// z+1, z−1, z−2 (Dobashi 2000).
pub const NEIGHBOURS: [[i32; 3]; 11] = [
    [1, 0, 0],
    [-1, 0, 0],
    [2, 0, 0],
    [-2, 0, 0],
    [0, 1, 0],
    [0, -1, 0],
    [0, 2, 0],
    [0, -2, 0],
    [0, 0, 1],
    [0, 0, -1],
    [0, 0, -2],
];

/// The cell at `(x, y, z)` after applying the boundary rule, or `None` if it is
/// outside (and so reads as empty). Only x and y wrap, and only when periodic.
fn resolve(size: GridSize, boundary: Boundary, x: i64, y: i64, z: i64) -> Option<usize> {
    let (nx, ny, nz) = (i64::from(size.nx), i64::from(size.ny), i64::from(size.nz));
    if !(0..nz).contains(&z) {
        return None;
    }
    let (x, y) = match boundary {
        Boundary::Periodic => (x.rem_euclid(nx), y.rem_euclid(ny)),
        Boundary::Empty => {
            if !(0..nx).contains(&x) || !(0..ny).contains(&y) {
                return None;
            }
            (x, y)
        }
    };
    Some(size.index_unchecked(x as u32, y as u32, z as u32))
}

/// Whether the event of stream `stream` happens in cell `(x, y, z)` during `step`,
/// spelled out cell by cell (see [`crate::rng`]): the cell's one uniform 16-bit number
/// is below its threshold, the base threshold scaled by the cell's mask level with
/// ellipsoids ([`lane_threshold`]: `l / 256` for supply and activation, `1 - l / 256`
/// for extinction), the base threshold itself without.
fn event(model: &Model, stream: u32, step: u32, x: u32, y: u32, z: u32) -> bool {
    let size = model.size();
    let wpr = size.words_per_row() as u32;
    let word = x / 32 + wpr * (y + size.ny * z);
    let lane = x % 32;
    let base = model.thresholds()[stream as usize];
    let threshold = if model.has_regions() {
        lane_threshold(base, u32::from(model.mask_level_unchecked(x, y, z)), stream)
    } else {
        base
    };
    // `&&` only skips a draw that cannot fire.
    threshold > 0 && uniform16(stream_key(model.seed(), step, stream), word, lane) < threshold
}

/// One automaton step `step` → `step + 1`, read entirely from `src`.
///
/// 1. rules: `hum' = hum ∧ ¬act`, `cld' = cld ∨ act`, `act' = ¬act ∧ hum ∧ f_act`;
/// 2. stochastic terms, each with its own draw: `cld' ∧= ¬ext`, `hum' ∨= sup`,
///    `act' ∨= act_draw`; clouds vanish where the mask level is 0;
/// 3. wind: slice `z` moves by [`Model::wind_shift`]`(z, step)` cells.
pub fn step(model: &Model, src: &NaiveState, step: u32) -> Result<NaiveState, Error> {
    src.check()?;
    let size = model.size();
    if src.size() != size {
        return Err(Error::SizeMismatch {
            what: "state",
            got: src.size().cells(),
            expected: size.cells(),
        });
    }
    let boundary = model.boundary();

    let mut next = NaiveState::empty(size)?;
    for z in 0..size.nz {
        for y in 0..size.ny {
            for x in 0..size.nx {
                let i = size.index_unchecked(x, y, z);
                let (hum, act, cld) = (src.hum[i], src.act[i], src.cld[i]);
                let f_act = NEIGHBOURS.iter().any(|[dx, dy, dz]| {
                    resolve(
                        size,
                        boundary,
                        i64::from(x) + i64::from(*dx),
                        i64::from(y) + i64::from(*dy),
                        i64::from(z) + i64::from(*dz),
                    )
                    .is_some_and(|j| src.act[j])
                });
                let mut hum_next = hum && !act;
                let mut cld_next = cld || act;
                let mut act_next = !act && hum && f_act;

                // Each event has its own draws; a draw only matters where the event
                // can change the cell, so the others are skipped (same result).
                if cld_next && event(model, STREAM_EXTINCTION, step, x, y, z) {
                    cld_next = false;
                }
                if !hum_next && event(model, STREAM_HUMIDITY, step, x, y, z) {
                    hum_next = true;
                }
                if !act_next && event(model, STREAM_ACTIVATION, step, x, y, z) {
                    act_next = true;
                }
                if model.mask_levels()[i] == 0 {
                    cld_next = false;
                }
                next.hum[i] = hum_next;
                next.act[i] = act_next;
                next.cld[i] = cld_next;
            }
        }
    }
    if !model.has_wind() {
        return Ok(next);
    }
    let mut moved = NaiveState::empty(size)?;
    for z in 0..size.nz {
        let [dx, dy] = model.wind_shift(z, step);
        for y in 0..size.ny {
            for x in 0..size.nx {
                let from = resolve(
                    size,
                    boundary,
                    i64::from(x) - i64::from(dx),
                    i64::from(y) - i64::from(dy),
                    i64::from(z),
                );
                if let Some(j) = from {
                    let i = size.index_unchecked(x, y, z);
                    moved.hum[i] = next.hum[j];
                    moved.act[i] = next.act[j];
                    moved.cld[i] = next.cld[j];
                }
            }
        }
    }
    Ok(moved)
}
