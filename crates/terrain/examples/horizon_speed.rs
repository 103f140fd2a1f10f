//! Times the 16-direction hull-sweep bake of `cargo xtask tradeoff terrain`'s speed
//! study (1024², 30 m, 2 km relief, seed 2010) and prints wall and CPU time, per
//! maximum distance, plus a checksum of the angles (to compare builds bit for bit).
//!
//! ```text
//! cargo run -p terrain --release --no-default-features --example horizon_speed -- \
//!     [SIDE] [THREADS] [REPEATS] [per-azimuth]
//! ```
//!
//! CPU time is the process's user + system time from `/proc/self/stat` (Linux; 10 ms
//! ticks), summed over all threads; `per-azimuth` also times each azimuth on its own.

use std::num::NonZeroUsize;
use std::time::Instant;

use terrain::generate::{GeneratorParams, generate};
use terrain::{Algorithm, HorizonOptions, bake_azimuths, bake_horizon};

/// User + system CPU seconds of this process (all threads), `None` off Linux.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the command name (which may hold spaces) start at state (3).
    let rest = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let utime: f64 = fields.get(11)?.parse().ok()?;
    let stime: f64 = fields.get(12)?.parse().ok()?;
    Some((utime + stime) / 100.0)
}

fn load() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_default()
}

fn checksum(angles: &[f32]) -> u64 {
    angles.iter().fold(0xcbf2_9ce4_8422_2325, |h, a| {
        (h ^ u64::from(a.to_bits())).wrapping_mul(0x100_0000_01b3)
    })
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let side: usize = args.first().map_or(Ok(1024), |s| s.parse())?;
    let threads: usize = args.get(1).map_or(Ok(2), |s| s.parse())?;
    let repeats: usize = args.get(2).map_or(Ok(3), |s| s.parse())?;
    let per_azimuth = args.get(3).is_some_and(|s| s == "per-azimuth");
    let hf = generate(&GeneratorParams {
        amplitude: 2000.0,
        wavelength: 7680.0,
        octaves: 7,
        ..GeneratorParams::new(side, side, 30.0, 2010)
    })?;
    // `HORIZON_SPEED_DISTANCES=none,6000`: only these (metres; `none`: unlimited).
    let distances: Vec<Option<f64>> = match std::env::var("HORIZON_SPEED_DISTANCES") {
        Ok(list) => list
            .split(',')
            .filter(|d| !d.is_empty())
            .map(|d| {
                if d == "none" {
                    Ok(None)
                } else {
                    d.parse().map(Some)
                }
            })
            .collect::<Result<_, _>>()?,
        Err(_) => vec![None, Some(6000.0), Some(2000.0)],
    };
    for max_distance in distances {
        let options = HorizonOptions {
            max_distance,
            threads: NonZeroUsize::new(threads),
            ..HorizonOptions::default()
        };
        let label = max_distance.map_or("unlimited".to_string(), |d| format!("{} km", d / 1e3));
        let mut walls = Vec::new();
        let mut cpus = Vec::new();
        let mut sum = 0;
        for _ in 0..repeats {
            let (c0, t0) = (cpu_seconds(), Instant::now());
            let maps = bake_azimuths(&hf, 16, &options, Algorithm::HullSweep)?;
            walls.push(t0.elapsed().as_secs_f64());
            if let (Some(a), Some(b)) = (c0, cpu_seconds()) {
                cpus.push(b - a);
            }
            sum = maps
                .layers()
                .iter()
                .fold(0u64, |h, l| h.rotate_left(5) ^ checksum(l.angles()));
        }
        let min = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
        println!(
            "{side}² {label:>9} {threads} threads: wall min {:.3} s, cpu min {:.2} s (walls {:?}) checksum {sum:016x} load {}",
            min(&walls),
            min(&cpus),
            walls.iter().map(|w| format!("{w:.3}")).collect::<Vec<_>>(),
            load()
        );
        if per_azimuth {
            let one = HorizonOptions {
                threads: NonZeroUsize::new(1),
                ..options
            };
            let mut line = String::new();
            for k in 0..16 {
                let azimuth = k as f64 * std::f64::consts::TAU / 16.0;
                let t0 = Instant::now();
                bake_horizon(&hf, azimuth, &one, Algorithm::HullSweep)?;
                line.push_str(&format!(" {:.0}", t0.elapsed().as_secs_f64() * 1e3));
            }
            println!("  per azimuth (ms, 1 thread, k·22.5°):{line}");
        }
    }
    Ok(())
}
