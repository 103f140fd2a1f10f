//! `cargo xtask tradeoff atmos` (being built in this change).

pub fn run(_options: &super::Options) -> Result<(), String> {
    Err("the atmos trade-off is not built yet".into())
}
