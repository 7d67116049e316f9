//! What `cargo xtask` shares with its tests: the model file's statement for the FMU built for
//! it (`model.rs`).

pub mod model;
