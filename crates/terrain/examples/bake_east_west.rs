//! Bakes the east/west pair of horizon maps (RGBA: normal in RGB, horizon angle in A; one map for
//! the sun in the east, one for the west) from a 16-bit greyscale PNG, or from a
//! generated heightfield when no file is given.
//!
//! ```text
//! cargo run -p terrain --release --example bake_east_west -- [heightmap.png SPACING_M SCALE_M_PER_COUNT OFFSET_M]
//! ```
//!
//! Writes `horizon_east.png` and `horizon_west.png` (16-bit RGBA) into
//! `$CARGO_TARGET_DIR` (default `target/`).

use std::path::PathBuf;
use std::time::Instant;

use terrain::generate::{GeneratorParams, generate};
use terrain::{Algorithm, BitDepth, Heightfield, HorizonOptions, NormalMap, bake_east_west};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let hf = match args.as_slice() {
        [] => {
            println!("no heightmap given: generating 1024 x 1024 at 30 m (seed 0)");
            generate(&GeneratorParams {
                amplitude: 2000.0,
                ..GeneratorParams::new(1024, 1024, 30.0, 0)
            })?
        }
        [path, spacing, scale, offset] => {
            Heightfield::open_png16(path, spacing.parse()?, scale.parse()?, offset.parse()?)?
        }
        _ => {
            return Err(
                "usage: bake_east_west [heightmap.png SPACING_M SCALE_M_PER_COUNT OFFSET_M]".into(),
            );
        }
    };
    let start = Instant::now();
    let normals = NormalMap::from_heightfield(&hf);
    let maps = bake_east_west(&hf, &HorizonOptions::default(), Algorithm::HullSweep)?;
    println!(
        "{} x {} texels: normals + east/west horizon in {:.3} s",
        hf.width(),
        hf.height(),
        start.elapsed().as_secs_f64()
    );
    let dir = PathBuf::from(std::env::var("CARGO_TARGET_DIR").unwrap_or_else(|_| "target".into()));
    std::fs::create_dir_all(&dir)?;
    for (name, map) in [("east", &maps.east), ("west", &maps.west)] {
        let path = dir.join(format!("horizon_{name}.png"));
        std::fs::write(&path, normals.to_rgba_png(map, BitDepth::Sixteen)?)?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
