//! The fast CPU implementation: 32 cells per `u32` word along x, bitwise rules,
//! neighbour shifts across words, random masks built 32 lanes at a time, rows split
//! over `std::thread::scope` threads. Every cell's result depends only on the previous
//! state and its own counter-based draws, so the output is independent of the thread
//! count and bit-identical to [`crate::naive`].

use crate::model::MIXED_LEVELS;
use crate::rng::{
    STREAM_ACTIVATION, STREAM_EXTINCTION, STREAM_HUMIDITY, THRESHOLD_ONE, draw_bits, stream_key,
};
use crate::{Boundary, Error, GridSize, Model, PackedState};

/// Below this many candidate cells a word's draws are made one set bit at a time;
/// from it on, all 32 lanes are hashed in a straight (vectorisable) loop. Either way
/// the same draws decide the same cells.
const DENSE_LANES: u32 = 4;

/// The events among `candidates` for a threshold shared by the whole word.
#[inline]
fn events_uniform(key: u32, base_cell: u32, candidates: u32, threshold: u32) -> u32 {
    if candidates == 0 || threshold == 0 {
        return 0;
    }
    if threshold >= THRESHOLD_ONE {
        return candidates;
    }
    if candidates.count_ones() >= DENSE_LANES {
        let mut bits = 0u32;
        for lane in 0..32u32 {
            let draw = draw_bits(key, base_cell.wrapping_add(lane)) >> 8;
            bits |= u32::from(draw < threshold) << lane;
        }
        bits & candidates
    } else {
        let mut bits = 0u32;
        let mut rest = candidates;
        while rest != 0 {
            let lane = rest.trailing_zeros();
            rest &= rest - 1;
            let draw = draw_bits(key, base_cell.wrapping_add(lane)) >> 8;
            bits |= u32::from(draw < threshold) << lane;
        }
        bits
    }
}

/// The events among `candidates` with one threshold per lane.
#[inline]
fn events_per_lane(key: u32, base_cell: u32, candidates: u32, thresholds: &[u32; 32]) -> u32 {
    if candidates == 0 {
        return 0;
    }
    let mut bits = 0u32;
    if candidates.count_ones() >= DENSE_LANES {
        for (lane, &t) in thresholds.iter().enumerate() {
            let draw = draw_bits(key, base_cell.wrapping_add(lane as u32)) >> 8;
            bits |= u32::from(draw < t) << lane;
        }
        bits & candidates
    } else {
        let mut rest = candidates;
        while rest != 0 {
            let lane = rest.trailing_zeros();
            rest &= rest - 1;
            let draw = draw_bits(key, base_cell.wrapping_add(lane)) >> 8;
            bits |= u32::from(draw < thresholds[lane as usize]) << lane;
        }
        bits
    }
}

struct Rules<'a> {
    model: &'a Model,
    src: &'a PackedState,
    size: GridSize,
    wpr: usize,
    periodic: bool,
    keys: [u32; 3],
    zero_row: Vec<u32>,
}

impl Rules<'_> {
    /// The `act` row at `(y, z)` after the boundary rule (a zero row outside).
    fn act_row(&self, y: i64, z: i64) -> &[u32] {
        let (ny, nz) = (i64::from(self.size.ny), i64::from(self.size.nz));
        if !(0..nz).contains(&z) {
            return &self.zero_row;
        }
        let y = if self.periodic {
            y.rem_euclid(ny)
        } else if (0..ny).contains(&y) {
            y
        } else {
            return &self.zero_row;
        };
        let row = (y + ny * z) as usize;
        &self.src.act[row * self.wpr..(row + 1) * self.wpr]
    }

    /// Computes rows `first_row..` into the output slices (whole rows).
    fn run(&self, first_row: usize, hum_out: &mut [u32], act_out: &mut [u32], cld_out: &mut [u32]) {
        let wpr = self.wpr;
        let size = self.size;
        let ny = size.ny as usize;
        let nx = size.nx as usize;
        let last_mask = size.last_word_mask();
        let thresholds = self.model.thresholds();
        let mask = self.model.mask_levels();
        let word_levels = self.model.word_levels();
        let alive = self.model.alive_words();
        let [key_ext, key_hum, key_act] = self.keys;
        let rows = hum_out.len() / wpr;
        for local in 0..rows {
            let row = first_row + local;
            let (y, z) = ((row % ny) as i64, (row / ny) as i64);
            let base = row * wpr;
            let act = &self.src.act[base..base + wpr];
            let hum = &self.src.hum[base..base + wpr];
            let cld = &self.src.cld[base..base + wpr];
            let neighbours = [
                self.act_row(y - 1, z),
                self.act_row(y + 1, z),
                self.act_row(y - 2, z),
                self.act_row(y + 2, z),
                self.act_row(y, z + 1),
                self.act_row(y, z - 1),
                self.act_row(y, z - 2),
            ];
            for wx in 0..wpr {
                let a = act[wx];
                let (prev, next) = match (wx > 0, wx + 1 < wpr) {
                    (true, true) => (act[wx - 1], act[wx + 1]),
                    (true, false) => (act[wx - 1], if self.periodic { act[0] } else { 0 }),
                    (false, true) => (if self.periodic { act[wpr - 1] } else { 0 }, act[wx + 1]),
                    (false, false) => {
                        if self.periodic {
                            (a, a)
                        } else {
                            (0, 0)
                        }
                    }
                };
                // bit i of `a << 1 | prev >> 31` is act(x - 1), and so on.
                let mut f_act = (a << 1 | prev >> 31)
                    | (a << 2 | prev >> 30)
                    | (a >> 1 | next << 31)
                    | (a >> 2 | next << 30);
                for n in &neighbours {
                    f_act |= n[wx];
                }
                let h = hum[wx];
                let c = cld[wx];
                let valid = if wx + 1 == wpr { last_mask } else { u32::MAX };
                let mut hum_next = h & !a;
                let mut cld_next = c | a;
                let mut act_next = !a & h & f_act;

                let word = base + wx;
                let base_cell = (wx * 32 + nx * row) as u32;
                let level = word_levels[word];
                if level != MIXED_LEVELS {
                    let [t_ext, t_hum, t_act] = thresholds[usize::from(level)];
                    if level == 0 {
                        cld_next = 0;
                    } else {
                        cld_next &= !events_uniform(key_ext, base_cell, cld_next, t_ext);
                    }
                    hum_next |= events_uniform(key_hum, base_cell, !hum_next & valid, t_hum);
                    act_next |= events_uniform(key_act, base_cell, !act_next & valid, t_act);
                } else {
                    let lanes = (nx - wx * 32).min(32);
                    let cells = &mask[base_cell as usize..base_cell as usize + lanes];
                    let mut t = [[0u32; 32]; 3];
                    for (lane, &l) in cells.iter().enumerate() {
                        let entry = thresholds[usize::from(l)];
                        t[0][lane] = entry[0];
                        t[1][lane] = entry[1];
                        t[2][lane] = entry[2];
                    }
                    cld_next &= alive[word];
                    cld_next &= !events_per_lane(key_ext, base_cell, cld_next, &t[0]);
                    hum_next |= events_per_lane(key_hum, base_cell, !hum_next & valid, &t[1]);
                    act_next |= events_per_lane(key_act, base_cell, !act_next & valid, &t[2]);
                }
                let out = local * wpr + wx;
                hum_out[out] = hum_next;
                act_out[out] = act_next;
                cld_out[out] = cld_next;
            }
        }
    }
}

fn check_pair(
    model: &Model,
    src: &PackedState,
    dst: &PackedState,
    threads: usize,
) -> Result<(), Error> {
    if threads == 0 {
        return Err(Error::ZeroThreads);
    }
    let size = model.size();
    for state in [src, dst] {
        state.check()?;
        if state.size() != size {
            return Err(Error::SizeMismatch {
                what: "state",
                got: state.size().cells(),
                expected: size.cells(),
            });
        }
    }
    Ok(())
}

/// Splits the rows of `dst` into `threads` contiguous chunks and runs `work(first_row,
/// hum, act, cld)` on each, in parallel when `threads > 1`.
fn split_rows<F>(size: GridSize, dst: &mut PackedState, threads: usize, work: F)
where
    F: Fn(usize, &mut [u32], &mut [u32], &mut [u32]) + Sync,
{
    let wpr = size.words_per_row();
    let rows = size.rows();
    let threads = threads.min(rows).max(1);
    if threads == 1 {
        work(0, &mut dst.hum, &mut dst.act, &mut dst.cld);
        return;
    }
    let per = rows.div_ceil(threads) * wpr;
    let work = &work;
    std::thread::scope(|scope| {
        let chunks = dst
            .hum
            .chunks_mut(per)
            .zip(dst.act.chunks_mut(per))
            .zip(dst.cld.chunks_mut(per))
            .enumerate();
        for (index, ((hum, act), cld)) in chunks {
            scope.spawn(move || work(index * per / wpr, hum, act, cld));
        }
    });
}

/// Rules and stochastic terms of `step` (no wind): `src` → `dst`, on `threads`
/// threads. `dst` is overwritten entirely; `src` is only read.
pub fn step_rules(
    model: &Model,
    src: &PackedState,
    dst: &mut PackedState,
    step: u32,
    threads: usize,
) -> Result<(), Error> {
    check_pair(model, src, dst, threads)?;
    let size = model.size();
    let seed = model.seed();
    let rules = Rules {
        model,
        src,
        size,
        wpr: size.words_per_row(),
        periodic: model.boundary() == Boundary::Periodic,
        keys: [
            stream_key(seed, step, STREAM_EXTINCTION),
            stream_key(seed, step, STREAM_HUMIDITY),
            stream_key(seed, step, STREAM_ACTIVATION),
        ],
        zero_row: vec![0; size.words_per_row()],
    };
    split_rows(size, dst, threads, |first, h, a, c| {
        rules.run(first, h, a, c)
    });
    Ok(())
}

/// 32 cells of `row` starting at cell `start` (may lie outside the row).
#[inline]
fn fetch_cells(row: &[u32], start: i64, periodic: bool) -> u32 {
    let wpr = row.len() as i64;
    let word = |q: i64| -> u32 {
        if periodic {
            row[q.rem_euclid(wpr) as usize]
        } else if (0..wpr).contains(&q) {
            row[q as usize]
        } else {
            0
        }
    };
    let q = start.div_euclid(32);
    let b = start.rem_euclid(32) as u32;
    if b == 0 {
        word(q)
    } else {
        word(q) >> b | word(q + 1) << (32 - b)
    }
}

/// Row `row` of `words`, or `zero` when the row lies outside the grid.
fn pick_row<'a>(words: &'a [u32], zero: &'a [u32], row: Option<usize>, wpr: usize) -> &'a [u32] {
    match row {
        Some(r) => &words[r * wpr..(r + 1) * wpr],
        None => zero,
    }
}

/// The wind pass of `step`: slice `z` of `src` moves by [`Model::wind_shift`]`(z,
/// step)` into `dst` (cells from outside are empty, or wrap when periodic).
pub fn apply_wind(
    model: &Model,
    src: &PackedState,
    dst: &mut PackedState,
    step: u32,
    threads: usize,
) -> Result<(), Error> {
    check_pair(model, src, dst, threads)?;
    let size = model.size();
    let wpr = size.words_per_row();
    let ny = size.ny as i64;
    let periodic = model.boundary() == Boundary::Periodic;
    let last_mask = size.last_word_mask();
    let zero_row = vec![0u32; wpr];
    split_rows(size, dst, threads, |first, hum_out, act_out, cld_out| {
        for local in 0..hum_out.len() / wpr {
            let row = first + local;
            let (y, z) = ((row as i64 % ny), (row as i64 / ny));
            let [dx, dy] = model.wind_shift(z as u32, step);
            let from_y = y - i64::from(dy);
            let from_y = if periodic {
                Some(from_y.rem_euclid(ny))
            } else {
                (0..ny).contains(&from_y).then_some(from_y)
            };
            let from_row = from_y.map(|fy| (fy + ny * z) as usize);
            let fields = [
                (pick_row(&src.hum, &zero_row, from_row, wpr), &mut *hum_out),
                (pick_row(&src.act, &zero_row, from_row, wpr), &mut *act_out),
                (pick_row(&src.cld, &zero_row, from_row, wpr), &mut *cld_out),
            ];
            for (src_row, out) in fields {
                for wx in 0..wpr {
                    let start = (wx as i64) * 32 - i64::from(dx);
                    let valid = if wx + 1 == wpr { last_mask } else { u32::MAX };
                    out[local * wpr + wx] = fetch_cells(src_row, start, periodic) & valid;
                }
            }
        }
    });
    Ok(())
}

/// One full step `step` → `step + 1` in place on `state`, using `scratch` (same size)
/// as the other ping-pong buffer: [`step_rules`], then [`apply_wind`] when the model
/// has wind.
pub fn step(
    model: &Model,
    state: &mut PackedState,
    scratch: &mut PackedState,
    step: u32,
    threads: usize,
) -> Result<(), Error> {
    step_rules(model, state, scratch, step, threads)?;
    if model.has_wind() {
        apply_wind(model, scratch, state, step, threads)
    } else {
        std::mem::swap(state, scratch);
        Ok(())
    }
}
