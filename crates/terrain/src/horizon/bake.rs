//! The entry points: one texel, one azimuth, the east/west pair, N azimuths.

use std::num::NonZeroUsize;

use super::exact::{Profile, brute_line, sweep_line};
use super::sampler::{LINE_BATCH, LineScratch, Sampler};
use super::{
    Algorithm, AzimuthHorizonMaps, EAST, EastWestHorizon, HorizonMap, HorizonOptions, Lines,
    MAX_AZIMUTHS, MIN_AZIMUTHS, NO_HORIZON, WEST, angle_from_tangent, check_azimuth, window,
};
use crate::{Heightfield, TerrainError};

/// The horizon angle of one texel (brute force on the documented sampling).
pub fn horizon_angle(
    hf: &Heightfield,
    x: usize,
    y: usize,
    azimuth: f64,
    options: &HorizonOptions,
) -> Result<f32, TerrainError> {
    options.validate()?;
    let azimuth = check_azimuth(azimuth)?;
    if x >= hf.width() {
        return Err(TerrainError::param("x", x as f64, "must be < width"));
    }
    if y >= hf.height() {
        return Err(TerrainError::param("y", y as f64, "must be < height"));
    }
    let lines = Lines::new(hf.width(), hf.height(), hf.spacing(), azimuth);
    let (c, _) = lines.locate(x, y);
    let target = y * hf.width() + x;
    if !lines.exact {
        let grid = lines.dominant_major(hf);
        let sampler = Sampler::new(
            &lines,
            &grid,
            options.inv_two_r(),
            lines.max_steps(options.max_distance),
        );
        let mut sc = LineScratch::default();
        sampler.build(c, &mut sc);
        sampler.brute(&mut sc);
        let k = sc
            .views
            .iter()
            .position(|v| v.texel == target)
            .expect("every texel lies on its own line");
        return Ok(sc.out[k]);
    }
    let mut texels = Vec::new();
    lines.texels(c, &mut texels);
    let target = y * hf.width() + x;
    let k = texels
        .iter()
        .position(|&t| t == target)
        .expect("every texel lies on its own line");
    let h: Vec<f64> = texels
        .iter()
        .map(|&t| f64::from(hf.samples()[t]) * hf.vertical_scale())
        .collect();
    let p = Profile {
        h: &h,
        step: lines.step,
        inv_two_r: options.inv_two_r(),
    };
    let end = k
        .saturating_add(lines.max_steps(options.max_distance))
        .min(h.len() - 1);
    let mut best = f64::NEG_INFINITY;
    for j in k + 1..=end {
        best = best.max(p.tangent(k, j));
    }
    Ok(angle_from_tangent(best))
}

/// Bakes the horizon map for one azimuth (radians clockwise from north).
pub fn bake_horizon(
    hf: &Heightfield,
    azimuth: f64,
    options: &HorizonOptions,
    algorithm: Algorithm,
) -> Result<HorizonMap, TerrainError> {
    bake_with(hf, azimuth, options, algorithm, None)
}

/// [`bake_horizon`], a maximum distance's hull sweep run by `method` where given
/// (else [`window::choose`]'s).
pub(super) fn bake_with(
    hf: &Heightfield,
    azimuth: f64,
    options: &HorizonOptions,
    algorithm: Algorithm,
    method: Option<window::Method>,
) -> Result<HorizonMap, TerrainError> {
    options.validate()?;
    let azimuth = check_azimuth(azimuth)?;
    let lines = Lines::new(hf.width(), hf.height(), hf.spacing(), azimuth);
    let max_steps = lines.max_steps(options.max_distance);
    let inv_two_r = options.inv_two_r();
    let scale = hf.vertical_scale();
    let samples = hf.samples();
    let method = method.unwrap_or_else(|| window::choose(&lines, max_steps));
    let by_unlimited = method == window::Method::ByUnlimited;
    if algorithm == Algorithm::HullSweep
        && method == window::Method::Rows
        && window::rows_apply(&lines, max_steps)
    {
        let grid = lines.dominant_major(hf);
        let angles = window::bake_rows(&lines, &grid, inv_two_r, max_steps, options.thread_count());
        return Ok(HorizonMap::from_angles(
            hf.width(),
            hf.height(),
            azimuth,
            angles,
        ));
    }
    let solve = |h: &[f64], g: &mut Vec<f64>, out: &mut [f32]| {
        let p = Profile {
            h,
            step: lines.step,
            inv_two_r,
        };
        match algorithm {
            Algorithm::BruteForce => brute_line(&p, max_steps, out),
            Algorithm::HullSweep => sweep_line(&p, max_steps, g, out),
        }
    };
    if lines.dominant_is_x && lines.offsets.iter().all(|&o| o == 0) {
        // East/west fast path: every line is a row, written in place.
        let width = hf.width();
        let mut angles = vec![NO_HORIZON; width * hf.height()];
        let threads = options.thread_count().clamp(1, hf.height());
        let reverse = lines.march < 0;
        let run_rows = |first_row: usize, block: &mut [f32]| {
            let (mut h, mut g, mut out) = (Vec::new(), Vec::new(), vec![0.0f32; width]);
            for (i, row_out) in block.chunks_mut(width).enumerate() {
                let row = &samples[(first_row + i) * width..][..width];
                h.clear();
                if reverse {
                    h.extend(row.iter().rev().map(|&v| f64::from(v) * scale));
                } else {
                    h.extend(row.iter().map(|&v| f64::from(v) * scale));
                }
                solve(&h, &mut g, &mut out);
                if reverse {
                    row_out
                        .iter_mut()
                        .zip(out.iter().rev())
                        .for_each(|(o, &v)| *o = v);
                } else {
                    row_out.copy_from_slice(&out);
                }
            }
        };
        if threads == 1 {
            run_rows(0, &mut angles);
        } else {
            // Blocks of rows handed out on demand, so that a thread slowed down by other
            // work on the machine does not hold up the others.
            const ROWS_PER_BLOCK: usize = 16;
            let blocks = std::sync::Mutex::new(
                angles
                    .chunks_mut(ROWS_PER_BLOCK * width)
                    .enumerate()
                    .map(|(b, block)| (b * ROWS_PER_BLOCK, block)),
            );
            std::thread::scope(|scope| {
                for _ in 0..threads {
                    let (blocks, run_rows) = (&blocks, &run_rows);
                    scope.spawn(move || {
                        loop {
                            // A poisoned lock means another worker panicked; the scope
                            // re-raises that panic, so this one just stops.
                            let next = match blocks.lock() {
                                Ok(mut iter) => iter.next(),
                                Err(_) => None,
                            };
                            let Some((first_row, block)) = next else {
                                break;
                            };
                            run_rows(first_row, block);
                        }
                    });
                }
            });
        }
        return Ok(HorizonMap {
            width,
            height: hf.height(),
            azimuth,
            angles,
        });
    }
    let ids: Vec<i64> = lines.ids().collect();
    let threads = options.thread_count().clamp(1, ids.len());
    let texels_total = hf.width() * hf.height();
    let grid = if lines.exact {
        Vec::new()
    } else {
        lines.dominant_major(hf)
    };
    let sampler = if lines.exact {
        None
    } else {
        let mut s = Sampler::new(&lines, &grid, inv_two_r, max_steps);
        s.by_unlimited = by_unlimited;
        Some(s)
    };
    // Solves the lines of `chunk` in order, handing each texel's angle to `emit`
    // (texel index, angle) in line order.
    let run_chunk = |chunk: &[i64], emit: &mut dyn FnMut(usize, f32)| {
        if let Some(sampler) = &sampler {
            let mut scs: Vec<LineScratch> =
                (0..LINE_BATCH).map(|_| LineScratch::default()).collect();
            let mut cursors = [0usize; LINE_BATCH];
            for batch in chunk.chunks(LINE_BATCH) {
                let scs = &mut scs[..batch.len()];
                sampler.build_batch(batch, scs);
                for sc in scs.iter_mut() {
                    match algorithm {
                        Algorithm::BruteForce => sampler.brute(sc),
                        Algorithm::HullSweep => sampler.sweep(sc),
                    }
                }
                // Row by row across the batch: neighbouring texels one after another.
                cursors.fill(0);
                for i in 0..lines.n_dominant {
                    for (sc, cursor) in scs.iter().zip(cursors.iter_mut()) {
                        if let Some(v) = sc.views.get(*cursor)
                            && v.i == i
                        {
                            emit(v.texel, sc.out[*cursor]);
                            *cursor += 1;
                        }
                    }
                }
            }
            return;
        }
        let (mut texels, mut h, mut g, mut out) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for &c in chunk {
            lines.texels(c, &mut texels);
            if texels.is_empty() {
                continue;
            }
            h.clear();
            h.extend(texels.iter().map(|&t| f64::from(samples[t]) * scale));
            out.clear();
            out.resize(texels.len(), 0.0f32);
            solve(&h, &mut g, &mut out);
            for (&t, &a) in texels.iter().zip(&out) {
                emit(t, a);
            }
        }
    };
    let mut angles = vec![NO_HORIZON; texels_total];
    if threads == 1 {
        // One worker writes straight into the map.
        run_chunk(&ids, &mut |t, a| angles[t] = a);
    } else {
        // Contiguous chunks of lines with about equal texel counts.
        let mut chunks: Vec<&[i64]> = Vec::with_capacity(threads);
        {
            let mut scratch = Vec::new();
            let mut start = 0;
            let mut acc = 0;
            for (i, &c) in ids.iter().enumerate() {
                lines.texels(c, &mut scratch);
                acc += scratch.len();
                if acc * threads >= texels_total * (chunks.len() + 1) && chunks.len() + 1 < threads
                {
                    chunks.push(&ids[start..=i]);
                    start = i + 1;
                }
            }
            chunks.push(&ids[start..]);
        }
        let per_chunk: Vec<Vec<(usize, f32)>> = std::thread::scope(|scope| {
            let handles: Vec<_> = chunks
                .iter()
                .map(|&chunk| {
                    let run_chunk = &run_chunk;
                    scope.spawn(move || {
                        let mut results = Vec::new();
                        run_chunk(chunk, &mut |t, a| results.push((t, a)));
                        results
                    })
                })
                .collect();
            handles
                .into_iter()
                .map(|h| h.join().expect("horizon worker panicked"))
                .collect()
        });
        // Scatter the line-ordered results into the row-major map.
        for &(t, a) in per_chunk.iter().flatten() {
            angles[t] = a;
        }
    }
    Ok(HorizonMap {
        width: hf.width(),
        height: hf.height(),
        azimuth,
        angles,
    })
}

/// Bakes the east and west maps ([`EAST`], [`WEST`]).
pub fn bake_east_west(
    hf: &Heightfield,
    options: &HorizonOptions,
    algorithm: Algorithm,
) -> Result<EastWestHorizon, TerrainError> {
    Ok(EastWestHorizon {
        east: bake_horizon(hf, EAST, options, algorithm)?,
        west: bake_horizon(hf, WEST, options, algorithm)?,
    })
}

/// Bakes `count` (4..=64) equally spaced azimuths, layer `k` at `k · 2π / count`.
pub fn bake_azimuths(
    hf: &Heightfield,
    count: usize,
    options: &HorizonOptions,
    algorithm: Algorithm,
) -> Result<AzimuthHorizonMaps, TerrainError> {
    if !(MIN_AZIMUTHS..=MAX_AZIMUTHS).contains(&count) {
        return Err(TerrainError::param(
            "count",
            count as f64,
            "number of azimuths must be in 4..=64",
        ));
    }
    options.validate()?;
    let azimuth = |k: usize| k as f64 * std::f64::consts::TAU / count as f64;
    let threads = options.thread_count().clamp(1, count);
    if threads == 1 {
        let layers = (0..count)
            .map(|k| bake_horizon(hf, azimuth(k), options, algorithm))
            .collect::<Result<Vec<_>, _>>()?;
        return Ok(AzimuthHorizonMaps { layers });
    }
    // Whole azimuths are handed out on demand to the workers, each baked on one
    // thread (no scatter, no per-azimuth start-up of threads); the azimuths off the
    // axes and diagonals, about twice the work, go first so that the last ones to
    // finish are short. Every map is computed the same way whatever the thread count.
    let one = HorizonOptions {
        threads: NonZeroUsize::new(1),
        ..*options
    };
    let mut order: Vec<usize> = (0..count).collect();
    order.sort_by_key(|&k| Lines::new(hf.width(), hf.height(), 1.0, azimuth(k)).exact);
    let next = std::sync::atomic::AtomicUsize::new(0);
    let slots: Vec<std::sync::Mutex<Option<Result<HorizonMap, TerrainError>>>> =
        (0..count).map(|_| std::sync::Mutex::new(None)).collect();
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    let Some(&k) = order.get(i) else {
                        break;
                    };
                    let map = bake_horizon(hf, azimuth(k), &one, algorithm);
                    // A poisoned lock means another worker panicked; the scope
                    // re-raises that panic.
                    if let Ok(mut slot) = slots[k].lock() {
                        *slot = Some(map);
                    }
                }
            });
        }
    });
    let layers = slots
        .into_iter()
        .map(|slot| {
            slot.into_inner()
                .ok()
                .flatten()
                .expect("every azimuth was baked")
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(AzimuthHorizonMaps { layers })
}
