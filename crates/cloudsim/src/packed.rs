//! The fast CPU implementation: 32 cells per `u32` word along x. For each run of rows
//! of one z slice, the bitwise rules run as vectorised loops over contiguous word
//! ranges (every neighbour row is another contiguous range; funnel shifts carry x
//! across words); then the three draws of 16 words at a time are compared bit-sliced
//! with the lanes' thresholds in SIMD registers ([`crate::rng`]), only on the words
//! an ellipsoid touches ([`crate::regions`]). Blocks of rows are dealt over
//! `std::thread::scope` threads, and the kernel is compiled again for AVX-512 and for
//! AVX2, picked at run time on x86-64 CPUs that have them. Every cell's result depends only on
//! the previous state and its own counter-based draws, so the output is independent of
//! the thread count and the instruction set, and bit-identical to [`crate::naive`].

use crate::regions::RegionTable;
use crate::rng::{
    LANE_PLANES, Lanes, STREAM_ACTIVATION, STREAM_EXTINCTION, STREAM_HUMIDITY, WORD_BATCH,
    below_lane_thresholds_batch, stream_key, uniform_threshold_planes, word_key,
};
use crate::{Boundary, Error, GridSize, Model, PackedState};

/// Where the draws' thresholds come from.
enum Draws<'a> {
    /// All three probabilities are 0: the rules alone.
    None,
    /// No ellipsoids: one threshold per stream for every cell, as planes (plane `k`
    /// of the three streams of 16 words, as the region table's groups).
    Uniform(Box<[[Lanes; 3]; LANE_PLANES]>),
    /// Ellipsoids: the per-lane planes of the words they touch.
    Regions(&'a RegionTable),
}

/// Everything one step's row kernel reads.
struct Rules<'a> {
    src: &'a PackedState,
    size: GridSize,
    wpr: usize,
    periodic: bool,
    draws: Draws<'a>,
    /// Keys of the extinction, humidity and activation streams of this step.
    keys: [u32; 3],
    /// Zeros, one z slice long: the `act` of a slice outside the grid.
    zero_run: Vec<u32>,
}

/// `dst[i] |= src[i]` (a loop the compiler vectorises).
#[inline(always)]
fn or_into(dst: &mut [u32], src: &[u32]) {
    for (d, &s) in dst.iter_mut().zip(src) {
        *d |= s;
    }
}

/// Bits `x - 1` and `x - 2` of the cells at the start of a word, from the word before.
#[inline(always)]
fn carry_from_previous(previous: u32) -> u32 {
    previous >> 31 | previous >> 30
}

/// Bits `x + 1` and `x + 2` of the cells at the end of a word, from the word after.
#[inline(always)]
fn carry_from_next(next: u32) -> u32 {
    next << 31 | next << 30
}

impl Rules<'_> {
    /// Computes rows `first_row..first_row + hum_out.len() / wpr` into the output
    /// slices, one run of rows of the same z slice at a time: every neighbour term is
    /// a contiguous range of another row run, ORed in with vectorised loops.
    #[inline(always)]
    fn run(&self, first_row: usize, hum_out: &mut [u32], act_out: &mut [u32], cld_out: &mut [u32]) {
        let wpr = self.wpr;
        let ny = self.size.ny as usize;
        let rows = hum_out.len() / wpr;
        let mut f_act = vec![0u32; ny.min(rows) * wpr];
        let mut carry = vec![0u32; ny.min(rows) * wpr];
        let mut local = 0;
        while local < rows {
            let row = first_row + local;
            let (y0, z) = (row % ny, row / ny);
            let run_rows = (ny - y0).min(rows - local);
            let words = local * wpr..(local + run_rows) * wpr;
            self.rules_run(
                z,
                y0,
                run_rows,
                &mut f_act,
                &mut carry,
                &mut hum_out[words.clone()],
                &mut act_out[words.clone()],
                &mut cld_out[words.clone()],
            );
            self.stochastic_run(
                row,
                run_rows,
                &mut hum_out[words.clone()],
                &mut act_out[words.clone()],
                &mut cld_out[words],
            );
            local += run_rows;
        }
    }

    /// The deterministic rules for rows `y0..y0 + run_rows` of slice `z`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn rules_run(
        &self,
        z: usize,
        y0: usize,
        run_rows: usize,
        f_act: &mut [u32],
        carry: &mut [u32],
        hum_out: &mut [u32],
        act_out: &mut [u32],
        cld_out: &mut [u32],
    ) {
        let wpr = self.wpr;
        let (ny, nz) = (self.size.ny as usize, self.size.nz as usize);
        let n = run_rows * wpr;
        let slice_words = ny * wpr;
        let base = (z * ny + y0) * wpr;
        let act = &self.src.act[base..base + n];
        let f = &mut f_act[..n];
        // z + 1, z - 1, z - 2: the same rows of the other slices (z never wraps; a
        // slice outside reads as the zero run)
        let z_neighbour = |dz: isize| -> &[u32] {
            let zz = z as isize + dz;
            if (0..nz as isize).contains(&zz) {
                let from = base.wrapping_add_signed(dz * slice_words as isize);
                &self.src.act[from..from + n]
            } else {
                &self.zero_run[..n]
            }
        };
        let (zp1, zm1, zm2) = (z_neighbour(1), z_neighbour(-1), z_neighbour(-2));
        // x ± 1, x ± 2 inside each word, and the z terms, in one pass
        for i in 0..n {
            let a = act[i];
            f[i] = a << 1 | a << 2 | a >> 1 | a >> 2 | zp1[i] | zm1[i] | zm2[i];
        }
        // y ± 1, y ± 2: rows of the same slice, wrapped when periodic
        let slice = &self.src.act[z * slice_words..(z + 1) * slice_words];
        for dy in [1isize, -1, 2, -2] {
            // rows y of the run whose y + dy lies inside the slice
            let lo = (y0 as isize).max(-dy) as usize;
            let hi = ((y0 + run_rows) as isize)
                .min(ny as isize - dy)
                .max(lo as isize) as usize;
            if hi > lo {
                let from = (lo as isize + dy) as usize * wpr;
                or_into(
                    &mut f[(lo - y0) * wpr..(hi - y0) * wpr],
                    &slice[from..from + (hi - lo) * wpr],
                );
            }
            if self.periodic {
                for y in y0..y0 + run_rows {
                    let yy = y as isize + dy;
                    if !(0..ny as isize).contains(&yy) {
                        let from = yy.rem_euclid(ny as isize) as usize * wpr;
                        or_into(
                            &mut f[(y - y0) * wpr..(y - y0 + 1) * wpr],
                            &slice[from..from + wpr],
                        );
                    }
                }
            }
        }
        // x carries across words: flat over the run, then the row ends redone
        let carry = &mut carry[..n];
        if n >= 2 {
            let inner = carry[1..n - 1].iter_mut().zip(&act[..n - 2]).zip(&act[2..]);
            for ((c, &previous), &next) in inner {
                *c = carry_from_previous(previous) | carry_from_next(next);
            }
        }
        for r in 0..run_rows {
            let row = &act[r * wpr..(r + 1) * wpr];
            // the words just outside the row along x (wrapped when periodic)
            let (before, after) = if self.periodic {
                (row[wpr - 1], row[0])
            } else {
                (0, 0)
            };
            let first = r * wpr;
            let last = first + wpr - 1;
            let inner_next = if wpr > 1 { row[1] } else { after };
            let inner_previous = if wpr > 1 { row[wpr - 2] } else { before };
            carry[first] = carry_from_previous(before) | carry_from_next(inner_next);
            carry[last] = carry_from_previous(inner_previous) | carry_from_next(after);
        }
        // the rules
        let hum = &self.src.hum[base..base + n];
        let cld = &self.src.cld[base..base + n];
        for i in 0..n {
            let (h, a) = (hum[i], act[i]);
            hum_out[i] = h & !a;
            cld_out[i] = cld[i] | a;
            act_out[i] = !a & h & (f[i] | carry[i]);
        }
        // the last word's padding lanes stay empty
        let last_mask = self.size.last_word_mask();
        for r in 0..run_rows {
            act_out[r * wpr + wpr - 1] &= last_mask;
        }
    }

    /// The three stochastic terms for `run_rows` rows from `first_row` (rules already
    /// applied to the outputs), 16 words at a time: each draw is compared bit-sliced
    /// with the lanes' thresholds and only for the lanes it can change.
    #[inline(always)]
    fn stochastic_run(
        &self,
        first_row: usize,
        run_rows: usize,
        hum_out: &mut [u32],
        act_out: &mut [u32],
        cld_out: &mut [u32],
    ) {
        let wpr = self.wpr;
        let first_word = first_row * wpr;
        match &self.draws {
            Draws::None => {}
            Draws::Uniform(planes) => {
                let last_mask = self.size.last_word_mask();
                let n = run_rows * wpr;
                for start in (0..n).step_by(WORD_BATCH) {
                    let count = WORD_BATCH.min(n - start);
                    let local: [usize; WORD_BATCH] =
                        std::array::from_fn(|i| start + i.min(count - 1));
                    let words = local.map(|l| (first_word + l) as u32);
                    let live = local.map(|l| {
                        if l % wpr == wpr - 1 {
                            last_mask
                        } else {
                            u32::MAX
                        }
                    });
                    self.draw_batch(
                        words,
                        local,
                        live,
                        0..count,
                        hum_out,
                        act_out,
                        cld_out,
                        |k| planes[k],
                    );
                }
            }
            Draws::Regions(table) => {
                // clouds vanish outside the entries (no cell above level 0 there)
                let first_entry = table.row_entries(first_row).start;
                let mut end_entry = first_entry;
                for r in 0..run_rows {
                    let row_entries = table.row_entries(first_row + r);
                    let row_words = &mut cld_out[r * wpr..(r + 1) * wpr];
                    if row_entries.is_empty() {
                        row_words.fill(0);
                        continue;
                    }
                    let first = table.word(row_entries.start) as usize % wpr;
                    let last = table.word(row_entries.end - 1) as usize % wpr;
                    row_words[..first].fill(0);
                    row_words[last + 1..].fill(0);
                    end_entry = row_entries.end;
                }
                if end_entry == first_entry {
                    return;
                }
                // whole groups of the table; the run's entries are lanes `lo..hi` of
                // its first and last group (the neighbouring runs draw the others)
                for group in first_entry / WORD_BATCH..end_entry.div_ceil(WORD_BATCH) {
                    let e0 = group * WORD_BATCH;
                    let lo = first_entry.saturating_sub(e0);
                    let hi = WORD_BATCH.min(end_entry - e0);
                    let real = |i: usize| (lo..hi).contains(&i);
                    let entry = |i: usize| if real(i) { e0 + i } else { e0 + lo };
                    let words: [u32; WORD_BATCH] = std::array::from_fn(|i| table.word(entry(i)));
                    let local: [usize; WORD_BATCH] =
                        std::array::from_fn(|i| words[i] as usize - first_word);
                    let alive = table.group_alive(group);
                    let live = std::array::from_fn(|i| if real(i) { alive[i] } else { 0 });
                    self.draw_batch(words, local, live, lo..hi, hum_out, act_out, cld_out, |k| {
                        table.group_plane(group, k)
                    });
                }
            }
        }
    }

    /// The three draws of 16 words (`local`: their index in the outputs; `live`: the
    /// lanes that hold a cell above mask level 0, 0 in slots that are not drawn) and
    /// the write-back of slots `real`.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn draw_batch(
        &self,
        words: [u32; WORD_BATCH],
        local: [usize; WORD_BATCH],
        live: [u32; WORD_BATCH],
        real: std::ops::Range<usize>,
        hum_out: &mut [u32],
        act_out: &mut [u32],
        cld_out: &mut [u32],
        planes: impl Fn(usize) -> [Lanes; 3],
    ) {
        const B: usize = WORD_BATCH;
        let mut cld = [0u32; B];
        let mut hum = [0u32; B];
        let mut act = [0u32; B];
        for i in 0..B {
            cld[i] = cld_out[local[i]] & live[i];
            hum[i] = hum_out[local[i]];
            act[i] = act_out[local[i]];
        }
        // the three streams side by side: extinction, humidity, activation
        let mut keys = [[0u32; B]; 3];
        let mut candidates = [[0u32; B]; 3];
        for i in 0..B {
            for (s, stream_keys) in keys.iter_mut().enumerate() {
                stream_keys[i] = word_key(self.keys[s], words[i]);
            }
            candidates[0][i] = cld[i];
            candidates[1][i] = !hum[i] & live[i];
            candidates[2][i] = !act[i] & live[i];
        }
        let [ext, sup, spark] = below_lane_thresholds_batch(&keys, &candidates, planes);
        for i in 0..B {
            cld[i] &= !ext[i];
            hum[i] |= sup[i];
            act[i] |= spark[i];
        }
        for i in real {
            cld_out[local[i]] = cld[i];
            hum_out[local[i]] = hum[i];
            act_out[local[i]] = act[i];
        }
    }
}

/// Runtime CPU-feature dispatch of the row kernel: every function of the kernel is
/// `#[inline(always)]`, so [`Rules::run`] is compiled for the crate's target and (on
/// x86-64) with AVX-512 (the 16 words of a draw fill one register) and with AVX2 (two
/// registers), both with native 32-bit multiplies, picked at run time. Integer
/// operations only: every build gives the same bits.
mod dispatch {
    #![allow(unsafe_code)]

    use super::Rules;

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn run_avx2(
        rules: &Rules,
        first_row: usize,
        hum: &mut [u32],
        act: &mut [u32],
        cld: &mut [u32],
    ) {
        rules.run(first_row, hum, act, cld);
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f,avx512bw,avx512vl")]
    fn run_avx512(
        rules: &Rules,
        first_row: usize,
        hum: &mut [u32],
        act: &mut [u32],
        cld: &mut [u32],
    ) {
        rules.run(first_row, hum, act, cld);
    }

    /// [`Rules::run`], with AVX-512 or AVX2 when the CPU has it.
    pub(super) fn run(
        rules: &Rules,
        first_row: usize,
        hum: &mut [u32],
        act: &mut [u32],
        cld: &mut [u32],
    ) {
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx512f")
            && std::is_x86_feature_detected!("avx512bw")
            && std::is_x86_feature_detected!("avx512vl")
        {
            // SAFETY: the only precondition of calling a `#[target_feature(enable =
            // "avx512f,avx512bw,avx512vl")]` function is that the CPU supports those
            // features, checked just above.
            unsafe { run_avx512(rules, first_row, hum, act, cld) };
            return;
        }
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx2") {
            // SAFETY: the only precondition of calling a `#[target_feature(enable =
            // "avx2")]` function is that the CPU supports AVX2, checked just above.
            unsafe { run_avx2(rules, first_row, hum, act, cld) };
            return;
        }
        rules.run(first_row, hum, act, cld);
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
    let rules = Rules::new(model, src, step);
    split_rows(model.size(), dst, threads, |first, h, a, c| {
        dispatch::run(&rules, first, h, a, c)
    });
    Ok(())
}

impl<'a> Rules<'a> {
    /// The kernel of `step` reading `src` (sizes already checked).
    fn new(model: &'a Model, src: &'a PackedState, step: u32) -> Self {
        let size = model.size();
        let seed = model.seed();
        let streams = [STREAM_EXTINCTION, STREAM_HUMIDITY, STREAM_ACTIVATION];
        let thresholds = model.thresholds();
        let draws = match model.regions() {
            Some(table) => Draws::Regions(table),
            None if thresholds == [0; 3] => Draws::None,
            None => {
                let planes = thresholds.map(uniform_threshold_planes);
                Draws::Uniform(Box::new(std::array::from_fn(|k| {
                    std::array::from_fn(|s| [planes[s][k]; WORD_BATCH])
                })))
            }
        };
        Self {
            src,
            size,
            wpr: size.words_per_row(),
            periodic: model.boundary() == Boundary::Periodic,
            draws,
            keys: streams.map(|s| stream_key(seed, step, s)),
            zero_run: vec![0; size.ny as usize * size.words_per_row()],
        }
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Config, Ellipsoid, Probabilities};

    /// The kernel built for the crate's target (no run-time dispatch) gives the same
    /// bits as the dispatched one (AVX-512 or AVX2 where the machine has it), with regions and
    /// without, periodic and not.
    #[test]
    fn baseline_and_dispatched_kernels_agree() {
        let size = GridSize::new(80, 24, 10);
        // the last case has probabilities 1, 1 and 0: "always" planes and a stream
        // with no stored bit plane in the region table
        for (periodic, regions, extremes) in [
            (false, true, false),
            (true, false, false),
            (false, false, false),
            (false, true, true),
        ] {
            let mut c = Config::new(if periodic {
                GridSize::new(64, 24, 10)
            } else {
                size
            });
            c.seed = 17;
            c.probabilities = if extremes {
                Probabilities {
                    extinction: 1.0,
                    humidity: 1.0,
                    activation: 0.0,
                }
            } else {
                Probabilities {
                    extinction: 0.3,
                    humidity: 0.2,
                    activation: 0.05,
                }
            };
            if periodic {
                c.boundary = Boundary::Periodic;
            }
            if regions {
                c.ellipsoids = vec![Ellipsoid {
                    center: [40.0, 12.0, 5.0],
                    radii: [30.0, 10.0, 4.0],
                }];
            }
            let model = Model::new(c).unwrap();
            let src = PackedState::random(model.size(), 5, 0.5, 0.2, 0.4).unwrap();
            let mut dispatched = PackedState::empty(model.size()).unwrap();
            step_rules(&model, &src, &mut dispatched, 9, 1).unwrap();
            let mut baseline = PackedState::empty(model.size()).unwrap();
            let rules = Rules::new(&model, &src, 9);
            rules.run(0, &mut baseline.hum, &mut baseline.act, &mut baseline.cld);
            let case = format!("periodic {periodic} regions {regions} extremes {extremes}");
            assert_eq!(baseline, dispatched, "{case}");
            let naive = crate::naive::step(&model, &src.to_naive(), 9).unwrap();
            assert_eq!(baseline.to_naive(), naive, "{case}");
        }
    }
}
