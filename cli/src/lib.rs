//! The library behind the `rotor-rub` command: building problems from presets, config files and
//! overrides, method options, trajectory passes, analyses (Poincaré sections, spectra, response
//! classes, sweeps), output files and plots. The binary (`main.rs`) parses the command line and
//! dispatches; the Python package (`python/`) calls the same functions, so both give the same
//! results and the same error messages.

pub mod analysis;
pub mod compare;
pub mod error;
pub mod fig2;
pub mod friction_fig;
pub mod limits;
pub mod merge;
pub mod options;
pub mod orbit;
pub mod output;
pub mod params;
pub mod plot;
pub mod poincare;
pub mod presets;
pub mod problem;
pub mod runup;
pub mod shard;
pub mod simulate;
pub mod spectrum;
pub mod stdio;
pub mod sweep;
pub mod trajectory;
pub mod watch;
