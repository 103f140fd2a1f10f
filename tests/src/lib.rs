//! Cross-crate and GPU tests live in tests/tests/.
