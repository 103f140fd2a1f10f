//! The fast CPU implementation: 32 cells per `u32` word along x, bitwise rules,
//! funnel shifts across neighbouring words, random masks built 32 lanes at a time
//! (bit-sliced comparisons, [`crate::rng`]) fused into the same pass over each row,
//! blocks of rows dealt over `std::thread::scope` threads. Every cell's result depends only on the previous
//! state and its own counter-based draws, so the output is independent of the thread
//! count and bit-identical to [`crate::naive`].

use crate::rng::{
    MASK_PLANE_ALIVE, MASK_PLANES, STREAM_ACTIVATION, STREAM_EXTINCTION, STREAM_HUMIDITY,
    STREAM_MASK_OFFSET, below_mask_level, below_threshold, stream_key,
};
use crate::{Boundary, Error, GridSize, Model, PackedState};

/// Everything one step's row kernel reads.
struct Rules<'a> {
    src: &'a PackedState,
    size: GridSize,
    wpr: usize,
    periodic: bool,
    regions: bool,
    mask_planes: &'a [u32],
    /// `[extinction, humidity, activation]` base thresholds.
    thresholds: [u32; 3],
    /// Base-draw keys of the three streams, then their mask-draw keys.
    keys: [u32; 6],
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

    /// The three stochastic terms of one word (rules already applied), fused into the
    /// row pass: each draw is built 32 lanes at a time, bit-sliced, and only for the
    /// lanes it can change (see [`crate::rng`]).
    #[inline]
    fn stochastic(&self, word: usize, valid: u32, hum: &mut u32, act: &mut u32, cld: &mut u32) {
        let [t_ext, t_hum, t_act] = self.thresholds;
        let [k_ext, k_hum, k_act, m_ext, m_hum, m_act] = self.keys;
        let w = word as u32;
        let planes = if self.regions {
            &self.mask_planes[word * MASK_PLANES..(word + 1) * MASK_PLANES]
        } else {
            &[]
        };
        let alive = if self.regions {
            planes[MASK_PLANE_ALIVE]
        } else {
            valid
        };
        // Clouds vanish where the mask level is 0 (seed 002); outside every ellipsoid
        // (most words) nothing can happen, so no draw is needed.
        *cld &= alive;
        if alive == 0 {
            return;
        }
        let mut ext = below_threshold(k_ext, w, *cld, t_ext);
        if self.regions && ext != 0 {
            // extinction grows away from the centres: probability p (1 - m)
            ext &= !below_mask_level(m_ext, w, ext, planes);
        }
        *cld &= !ext;
        let mut sup = below_threshold(k_hum, w, !*hum & alive, t_hum);
        if self.regions && sup != 0 {
            sup = below_mask_level(m_hum, w, sup, planes);
        }
        *hum |= sup;
        let mut spark = below_threshold(k_act, w, !*act & alive, t_act);
        if self.regions && spark != 0 {
            spark = below_mask_level(m_act, w, spark, planes);
        }
        *act |= spark;
    }

    /// Computes whole rows `first_row..` into the output slices.
    fn run(&self, first_row: usize, hum_out: &mut [u32], act_out: &mut [u32], cld_out: &mut [u32]) {
        let wpr = self.wpr;
        let ny = self.size.ny as usize;
        let last_mask = self.size.last_word_mask();
        let rows = hum_out.len() / wpr;
        for local in 0..rows {
            let row = first_row + local;
            let (y, z) = ((row % ny) as i64, (row / ny) as i64);
            let base = row * wpr;
            let act = &self.src.act[base..base + wpr];
            let hum = &self.src.hum[base..base + wpr];
            let cld = &self.src.cld[base..base + wpr];
            let (ym1, yp1, ym2, yp2) = (
                &self.act_row(y - 1, z)[..wpr],
                &self.act_row(y + 1, z)[..wpr],
                &self.act_row(y - 2, z)[..wpr],
                &self.act_row(y + 2, z)[..wpr],
            );
            let (zp1, zm1, zm2) = (
                &self.act_row(y, z + 1)[..wpr],
                &self.act_row(y, z - 1)[..wpr],
                &self.act_row(y, z - 2)[..wpr],
            );
            let out_h = &mut hum_out[local * wpr..(local + 1) * wpr];
            let out_a = &mut act_out[local * wpr..(local + 1) * wpr];
            let out_c = &mut cld_out[local * wpr..(local + 1) * wpr];
            // The words just outside the row along x (wrapped when periodic).
            let (before, after) = if self.periodic {
                (act[wpr - 1], act[0])
            } else {
                (0, 0)
            };
            for wx in 0..wpr {
                let a = act[wx];
                let prev = if wx > 0 { act[wx - 1] } else { before };
                let next = if wx + 1 < wpr { act[wx + 1] } else { after };
                // Funnel shifts across words: bit i of `a << 1 | prev >> 31` is
                // act(x - 1), and so on.
                let f_act = (a << 1 | prev >> 31)
                    | (a << 2 | prev >> 30)
                    | (a >> 1 | next << 31)
                    | (a >> 2 | next << 30)
                    | ym1[wx]
                    | yp1[wx]
                    | ym2[wx]
                    | yp2[wx]
                    | zp1[wx]
                    | zm1[wx]
                    | zm2[wx];
                let h = hum[wx];
                let valid = if wx + 1 == wpr { last_mask } else { u32::MAX };
                let mut hum_next = h & !a;
                let mut cld_next = cld[wx] | a;
                let mut act_next = !a & h & f_act & valid;
                self.stochastic(
                    base + wx,
                    valid,
                    &mut hum_next,
                    &mut act_next,
                    &mut cld_next,
                );
                out_h[wx] = hum_next;
                out_a[wx] = act_next;
                out_c[wx] = cld_next;
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

/// Blocks of rows handed out per thread: the work is uneven (draws happen only inside
/// the ellipsoids), so each thread gets several blocks spread over the grid.
const BLOCKS_PER_THREAD: usize = 8;

/// Splits the rows of `dst` into blocks, deals them round-robin to `threads` threads and
/// runs `work(first_row, hum, act, cld)` on each block, in parallel when `threads > 1`.
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
    let per = rows.div_ceil(threads * BLOCKS_PER_THREAD) * wpr;
    type Block<'b> = (usize, &'b mut [u32], &'b mut [u32], &'b mut [u32]);
    let mut dealt: Vec<Vec<Block>> = (0..threads).map(|_| Vec::new()).collect();
    let blocks = dst
        .hum
        .chunks_mut(per)
        .zip(dst.act.chunks_mut(per))
        .zip(dst.cld.chunks_mut(per))
        .enumerate();
    for (index, ((hum, act), cld)) in blocks {
        dealt[index % threads].push((index * per / wpr, hum, act, cld));
    }
    let work = &work;
    std::thread::scope(|scope| {
        for blocks in dealt {
            scope.spawn(move || {
                for (first, hum, act, cld) in blocks {
                    work(first, hum, act, cld);
                }
            });
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
    let streams = [STREAM_EXTINCTION, STREAM_HUMIDITY, STREAM_ACTIVATION];
    let base = streams.map(|s| stream_key(seed, step, s));
    let mask = streams.map(|s| stream_key(seed, step, s + STREAM_MASK_OFFSET));
    let rules = Rules {
        src,
        size,
        wpr: size.words_per_row(),
        periodic: model.boundary() == Boundary::Periodic,
        regions: model.has_regions(),
        mask_planes: model.all_mask_planes(),
        thresholds: model.thresholds(),
        keys: [base[0], base[1], base[2], mask[0], mask[1], mask[2]],
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
