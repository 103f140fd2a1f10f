//! `cargo xtask tradeoff terrain` (being built in this change).

pub fn run(_options: &super::Options) -> Result<(), String> {
    Err("the terrain trade-off is not built yet".into())
}
