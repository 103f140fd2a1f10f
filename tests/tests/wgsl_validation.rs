//! Every WGSL module of every crate, composed with its imports, passes naga.
//! (Each crate also validates its own modules; this catches cross-crate imports.)

#[test]
fn every_module_of_every_crate_validates() {
    let composer = render::composer();
    let mut count = 0;
    for name in composer.module_names() {
        let source = composer.compose_module(name).unwrap();
        if let Err(e) = skyscape_wgsl::validate(name, &source) {
            panic!("{e}");
        }
        count += 1;
    }
    assert!(count >= 9, "only {count} modules registered");
}
