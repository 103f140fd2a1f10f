//! CPU time (not wall time) per bit-packed step on one thread, at the criterion bench's
//! 256×256×64 grid with three ellipsoids and all stochastic terms, and for the rules
//! alone. On a shared machine wall-clock benches (criterion) include the time other
//! processes hold the core; the thread's own CPU time (`/proc/thread-self/stat`, 10 ms
//! ticks, median of 20 rounds of 60 steps) does not, so it complements `benches/step.rs`.
//! Linux only.
//!
//! `cargo run --release -p cloudsim --no-default-features --example step_cpu_time`

use cloudsim::{
    Config, Ellipsoid, GridSize, Model, PackedState, Probabilities, Simulation, naive, packed,
};

/// User + system CPU seconds of the calling thread.
fn thread_cpu_seconds() -> Result<f64, Box<dyn std::error::Error>> {
    let stat = std::fs::read_to_string("/proc/thread-self/stat")?;
    let after_name = stat.rfind(')').ok_or("malformed /proc/thread-self/stat")? + 2;
    let fields: Vec<&str> = stat[after_name..].split_whitespace().collect();
    let ticks: f64 = fields[11].parse::<f64>()? + fields[12].parse::<f64>()?;
    Ok(ticks / 100.0)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let size = GridSize::new(256, 256, 64);
    let mut c = Config::new(size);
    c.seed = 2000;
    c.ellipsoids = vec![
        Ellipsoid {
            center: [90.0, 100.0, 30.0],
            radii: [70.0, 60.0, 24.0],
        },
        Ellipsoid {
            center: [180.0, 160.0, 34.0],
            radii: [60.0, 70.0, 22.0],
        },
        Ellipsoid {
            center: [150.0, 60.0, 28.0],
            radii: [40.0, 40.0, 16.0],
        },
    ];
    let model = Model::new(c.clone())?;
    let mut sim = Simulation::new(model.clone())?;
    sim.advance(60)?;
    let mut rules = c;
    rules.ellipsoids.clear();
    rules.probabilities = Probabilities {
        extinction: 0.0,
        humidity: 0.0,
        activation: 0.0,
    };
    let rules = Model::new(rules)?;
    // The naive reference, best of 3 single steps.
    let reference = sim.state().to_naive();
    let mut naive_best = f64::MAX;
    for round in 0..3 {
        let start = thread_cpu_seconds()?;
        std::hint::black_box(naive::step(&model, &reference, 60 + round)?);
        naive_best = naive_best.min(thread_cpu_seconds()? - start);
    }
    println!(
        "naive: {:.1} ms CPU/step = {:.1} M cell-updates/s",
        naive_best * 1e3,
        size.cells() as f64 / naive_best / 1e6
    );
    for (name, m) in [("all stochastic terms", &model), ("rules alone", &rules)] {
        let mut state = sim.state().clone();
        let mut scratch = PackedState::empty(size)?;
        let steps = 60u32;
        let mut rounds = Vec::new();
        for round in 0..20 {
            let start = thread_cpu_seconds()?;
            for k in 0..steps {
                packed::step(m, &mut state, &mut scratch, 60 + round * steps + k, 1)?;
            }
            rounds.push((thread_cpu_seconds()? - start) / f64::from(steps));
        }
        // the median: tick accounting makes single rounds err by a tick either way, so
        // the fastest round is biased low
        rounds.sort_by(f64::total_cmp);
        let per_step = rounds[rounds.len() / 2];
        println!(
            "packed, {name}: {:.2} ms CPU/step on 1 thread (median of 20 rounds of 60 steps; \
             fastest {:.2} ms) = {:.2} G cell-updates/s per core ({:.0}x the naive step)",
            per_step * 1e3,
            rounds[0] * 1e3,
            size.cells() as f64 / per_step / 1e9,
            naive_best / per_step
        );
    }
    Ok(())
}
