//! Every WGSL module of every crate, composed with its imports, passes naga.
//! (Each crate also validates its own modules; this catches cross-crate imports.)

#[test]
fn every_module_of_every_crate_validates() {
    let mut composer = render::composer();
    composer
        .add_modules(terrain::WGSL_MODULES)
        .unwrap()
        .add_modules(cloudsim::WGSL_MODULES)
        .unwrap()
        .add_modules(cloudlight::WGSL_MODULES)
        .unwrap();
    let mut count = 0;
    for name in composer.module_names() {
        let source = composer.compose_module(name).unwrap();
        if let Err(e) = skyscape_wgsl::validate(name, &source) {
            panic!("{e}");
        }
        count += 1;
    }
    assert!(count >= 17, "only {count} modules registered");
}
